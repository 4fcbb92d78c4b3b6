#version 460
#extension GL_GOOGLE_include_directive : require
// Tree models' vertices (common/tree_vertex.glsl), cut away near the camera by a clip distance
// (the device's shaderClipDistance): the near fade's inner half never reaches the rasteriser.
#define VEGSTREAM_TREE_NEAR_CLIP 1
#include "common/tree_vertex.glsl"
