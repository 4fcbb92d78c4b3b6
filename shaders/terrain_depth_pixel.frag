#version 450
#extension GL_GOOGLE_include_directive : require
// The terrain rasterised in compute (render/terrain_raster_pass.h) into the depth attachment,
// one fragment per pixel, over the tiles where plants or trees may be drawn
// (render/terrain_depth_handover.h: a quad per run of tiles, terrain_depth_span.vert, or one
// full-screen triangle, sky.vert): each pixel's sample 0 depth into all its samples. Where they
// differ by more than common/terrain_raster.glsl's kDepthEdgeShare (an edge), terrain_depth_edge.vert's
// tiles write them per sample instead (terrain_depth.frag); elsewhere the one depth is off by no
// more than the terrain's own depth range across the pixel. So the trees and plants drawn after it
// are depth-tested against the terrain by the hardware, rejected before they are shaded.
#include "common/frame_uniforms.glsl"

layout(location = 0) in vec2 inNdc;  // sky.vert's, unused
layout(std430, set = 0, binding = 5) readonly buffer TerrainDepthSamples { float terrainDepthSamples[]; };

void main() {
  uint samples = uint(frame.terrainDepth.y);
  uvec2 px = uvec2(gl_FragCoord.xy);
  gl_FragDepth = terrainDepthSamples[(px.y * uint(frame.viewport.x) + px.x) * samples];
}
