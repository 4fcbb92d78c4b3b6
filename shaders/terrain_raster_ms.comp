#version 450
#extension GL_GOOGLE_include_directive : require
// The compute terrain rasteriser's raster and shade, multisampled (common/terrain_raster_shade.glsl).
#define VEGSTREAM_MULTISAMPLE 1
#include "terrain_raster_shade.glsl"
