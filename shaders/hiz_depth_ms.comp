#version 450
#extension GL_GOOGLE_include_directive : require
// Hi-Z level 0 from a multisampled depth target: every sample counts (render/hiz_pass.h,
// common/hiz_depth.glsl).
#define HIZ_MSAA 1
#include "hiz_depth.glsl"
