#version 450
#extension GL_GOOGLE_include_directive : require
// The terrain rasterised in compute (render/terrain_raster_pass.h) into the depth attachment,
// per sample (gl_SampleID): each sample's depth from the raster's buffer, over the tiles that hold
// a depth edge where plants or trees may be drawn (terrain_depth_edge.vert, render/terrain_depth_handover.h).
#include "common/frame_uniforms.glsl"

layout(location = 0) in vec2 inNdc;  // terrain_depth_edge.vert's, unused
layout(std430, set = 0, binding = 5) readonly buffer TerrainDepthSamples { float terrainDepthSamples[]; };

void main() {
  uint samples = uint(frame.terrainDepth.y);
  uvec2 px = uvec2(gl_FragCoord.xy);
  gl_FragDepth = terrainDepthSamples[(px.y * uint(frame.viewport.x) + px.x) * samples + uint(gl_SampleID)];
}
