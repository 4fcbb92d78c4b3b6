#version 450
#extension GL_GOOGLE_include_directive : require
// The terrain rasterised in compute (render/terrain_raster_pass.h) into the depth attachment:
// one full-screen triangle, run per sample (gl_SampleID), writes each sample's depth from the
// raster's buffer, so the trees and plants drawn after it are depth-tested against the terrain by
// the hardware — rejected before they are shaded — as over a terrain drawn with graphics.
#include "common/frame_uniforms.glsl"

layout(location = 0) in vec2 inNdc;  // sky.vert's, unused
layout(std430, set = 0, binding = 5) readonly buffer TerrainDepthSamples { float terrainDepthSamples[]; };

void main() {
  uint samples = uint(frame.terrainDepth.y);
  uvec2 px = uvec2(gl_FragCoord.xy);
  gl_FragDepth = terrainDepthSamples[(px.y * uint(frame.viewport.x) + px.x) * samples + uint(gl_SampleID)];
}
