#version 450
#extension GL_GOOGLE_include_directive : require
// Deferred terrain shading, one sample per pixel (common/terrain_shade.glsl).
#include "terrain_shade.glsl"
