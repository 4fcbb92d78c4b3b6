#version 450
#extension GL_GOOGLE_include_directive : require
// The visibility pass of deferred terrain shading (render/terrain_pass.h): each sample keeps
// which triangle it sees, 1 + the triangle's index in the frame's index buffer (0: none, the
// sky). Nothing else is computed here: on GPUs with few graphics units (NVIDIA's compute
// parts) fragment work is the scarce resource, so the shading runs in compute.
#include "terrain_draw.glsl"
layout(location = 0) flat in uint inPiece;
// The id's four bytes go out as UNORM (render/render_targets.h says why): byte k is written as
// (k + 0.25) / 255, which round-to-nearest and truncation both store as k.
layout(location = 0) out vec4 outTriangle;
void main() {
  uint id = drawPieces[inPiece].range.x + uint(gl_PrimitiveID) + 1u;
  uvec4 bytes = uvec4(id, id >> 8, id >> 16, id >> 24) & 0xffu;
  outTriangle = (vec4(bytes) + 0.25) / 255.0;
}
