#version 450
#extension GL_GOOGLE_include_directive : require
// Hi-Z level 0 from the depth samples of the terrain rasterised in compute (common/hiz_depth.glsl).
#define HIZ_BUFFER 1
#include "common/hiz_depth.glsl"
