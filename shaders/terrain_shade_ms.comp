#version 450
#extension GL_GOOGLE_include_directive : require
// Deferred terrain shading of a multisampled target (common/terrain_shade.glsl).
#define VEGSTREAM_MULTISAMPLE 1
#include "terrain_shade.glsl"
