#version 450
#extension GL_GOOGLE_include_directive : require
// The visibility pass of deferred terrain shading (render/terrain_pass.h): each sample keeps
// which triangle it sees, 1 + the triangle's index in the frame's index buffer (0: none, the
// sky). Nothing else is computed here: on GPUs with few graphics units (NVIDIA's compute
// parts) fragment work is the scarce resource, so the shading runs in compute.
#include "terrain_push.glsl"
layout(location = 0) out uint outTriangle;
void main() {
  outTriangle = push.ids.x + uint(gl_PrimitiveID) + 1u;
}
