#version 450
#extension GL_GOOGLE_include_directive : require
// The compute terrain rasteriser's raster and shade, one sample per pixel (common/terrain_raster_shade.glsl).
#include "terrain_raster_shade.glsl"
