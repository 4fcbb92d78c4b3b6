#version 450
#extension GL_GOOGLE_include_directive : require
// The terrain's depth edges into the depth attachment (render/terrain_raster_pass.h): one quad
// (instance) per 8 × 8-pixel tile the compute raster found a depth edge in (common/terrain_raster.glsl's
// DepthEdges: render/terrain_depth_handover.h), whose fragments terrain_depth.frag runs
// per sample. Clipped to the viewport where the last tiles reach past it.
#include "common/frame_uniforms.glsl"

layout(std430, set = 1, binding = 0) readonly buffer DepthEdgeTiles {
  uint depthEdgeCommand[4];
  uint depthEdgeTiles[];
};
layout(location = 0) out vec2 outNdc;  // terrain_depth.frag's input, unused

const uint kTile = 8u;  // common/terrain_raster.glsl's kRasterTile

void main() {
  uint tilesX = (uint(frame.viewport.x) + kTile - 1u) / kTile;
  uint tile = depthEdgeTiles[gl_InstanceIndex];
  // Two triangles: corners (0,0) (1,0) (0,1), (0,1) (1,0) (1,1).
  const uvec2 corners[6] = uvec2[](uvec2(0, 0), uvec2(1, 0), uvec2(0, 1), uvec2(0, 1), uvec2(1, 0), uvec2(1, 1));
  uvec2 px = (uvec2(tile % tilesX, tile / tilesX) + corners[gl_VertexIndex]) * kTile;
  vec2 at = min(vec2(px), frame.viewport.xy);
  outNdc = at * frame.viewport.zw * 2.0 - 1.0;
  gl_Position = vec4(outNdc, 0.0, 1.0);
}
