#version 450
// The multiple-scattering LUT (Hillaire 2020 §5.5; render/atmosphere_pass.h): Ψ_ms for each
// (sun cosine, altitude) over 10 × 20 directions (render/atmosphere_pass.h
// kMultiScatteringDirections), 20 steps each.
#extension GL_GOOGLE_include_directive : require
#include "common/atmosphere_lut_io.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
void main() {
  ivec2 size = imageSize(multiScatteringOut);
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (texel.x >= size.x || texel.y >= size.y) return;
  vec2 rMuS = multiScatteringRMuSFromUv(lutUvOfTexel(texel, size));
  imageStore(multiScatteringOut, texel, vec4(multiScatteringTransfer(rMuS.x, rMuS.y, 10, 20), 1.0));
}
