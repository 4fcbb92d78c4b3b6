#version 450
#extension GL_GOOGLE_include_directive : require
// The terrain's depth hand-over per pixel (render/terrain_depth_handover.h): one quad (instance)
// per run of wanted 8 × 8-pixel tiles along a row (terrain_depth_tiles.comp), whose fragments
// terrain_depth_pixel.frag runs once per pixel. Clipped to the viewport where the last tiles
// reach past it.
#include "common/frame_uniforms.glsl"

layout(std430, set = 1, binding = 0) readonly buffer DepthSpans {
  uint spanCommand[4];
  uint fullCommand[4];
  uvec4 spanTiles;
  uvec4 spans[];  // first tile, one past the last, row
};
layout(location = 0) out vec2 outNdc;  // terrain_depth_pixel.frag's input, unused

const uint kTile = 8u;  // common/terrain_raster.glsl's kRasterTile

void main() {
  uvec4 run = spans[gl_InstanceIndex];
  // Two triangles: corners (0,0) (1,0) (0,1), (0,1) (1,0) (1,1).
  const uvec2 corners[6] = uvec2[](uvec2(0, 0), uvec2(1, 0), uvec2(0, 1), uvec2(0, 1), uvec2(1, 0), uvec2(1, 1));
  uvec2 c = corners[gl_VertexIndex];
  uvec2 px = uvec2(c.x == 0u ? run.x : run.y, run.z + c.y) * kTile;
  vec2 at = min(vec2(px), frame.viewport.xy);
  outNdc = at * frame.viewport.zw * 2.0 - 1.0;
  gl_Position = vec4(outNdc, 0.0, 1.0);
}
