#ifndef TERRAIN_OCCLUSION_GLSL
#define TERRAIN_OCCLUSION_GLSL
// Fragment stages drawn over the terrain (plants, markers, trees). When the terrain was
// rasterised in compute (render/terrain_raster_pass.h: frame.terrainDepth.x = 1) its depth is not
// in the depth attachment, which then holds only what the plants and trees draw: each fragment
// tests itself against the terrain's depth per sample instead, and keeps the samples where it is
// nearer (reverse-Z: greater), as the hardware depth test against a terrain-filled attachment
// would. The fragment's depth at a sample is its plane's (depth is linear in screen space)
// at that sample's standard position. Otherwise every sample passes: the attachment tests.
// Needs frame_uniforms.glsl; call terrainDepthSlope() in uniform control flow (derivatives).
#include "sample_positions.glsl"

layout(std430, set = 0, binding = 5) readonly buffer TerrainDepthSamples { float terrainDepthSamples[]; };

vec2 terrainDepthSlope() { return vec2(dFdxFine(gl_FragCoord.z), dFdyFine(gl_FragCoord.z)); }

// The mask of this fragment's samples in front of the terrain (all bits when the attachment
// holds the terrain's depth).
uint terrainCoverage(vec2 slope) {
  if (frame.terrainDepth.x == 0.0) return 0xffffffffu;
  uint samples = uint(frame.terrainDepth.y);
  uvec2 px = uvec2(gl_FragCoord.xy);
  uint base = (px.y * uint(frame.viewport.x) + px.x) * samples;
  uint mask = 0u;
  for (uint s = 0u; s < samples; ++s) {
    vec2 offset = samplePosition(samples, s) - 0.5;
    if (gl_FragCoord.z + dot(slope, offset) > terrainDepthSamples[base + s]) mask |= 1u << s;
  }
  return mask;
}
#endif
