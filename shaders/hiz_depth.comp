#version 450
#extension GL_GOOGLE_include_directive : require
// Hi-Z level 0 from a single-sample depth target (render/hiz_pass.h, common/hiz_depth.glsl).
#include "hiz_depth.glsl"
