#version 450
// The transmittance LUT (render/atmosphere_pass.h): from each (r, mu) to the top of the
// atmosphere, 100 midpoint steps (grazing rays need them) (common/atmosphere_model.glsl).
#extension GL_GOOGLE_include_directive : require
#include "common/atmosphere_lut_io.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
void main() {
  ivec2 size = imageSize(transmittanceOut);
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (texel.x >= size.x || texel.y >= size.y) return;
  vec2 rMu = transmittanceRMuFromUv(lutUvOfTexel(texel, size));
  imageStore(transmittanceOut, texel, vec4(transmittanceToTopMarched(rMu.x, rMu.y, 100), 1.0));
}
