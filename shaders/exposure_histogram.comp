#version 450
// Automatic exposure, step 1 (common/exposure.glsl): the resolved HDR frame's log2-luminance
// histogram, per workgroup in shared memory, then added into the state's bins (integer
// atomics: the order of the adds does not change the counts).
#extension GL_GOOGLE_include_directive : require
#include "common/exposure.glsl"
layout(local_size_x = 16, local_size_y = 16) in;
layout(set = 0, binding = 0, r11f_g11f_b10f) uniform readonly image2D hdr;
layout(set = 0, binding = 1, std430) buffer State { ExposureState state; };
shared uint local[kExposureBins];

void main() {
  uint t = gl_LocalInvocationIndex;
  if (t < uint(kExposureBins)) local[t] = 0u;
  barrier();
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(hdr);
  if (px.x < size.x && px.y < size.y) {
    float lum = luminanceOf(imageLoad(hdr, px).rgb);
    float f = (log2(max(lum, 1e-12)) - kLogLumMin) / (kLogLumMax - kLogLumMin);
    int bin = clamp(int(f * float(kExposureBins)), 0, kExposureBins - 1);
    atomicAdd(local[bin], 1u);
  }
  barrier();
  if (t < uint(kExposureBins) && local[t] != 0u) atomicAdd(state.bins[t], local[t]);
}
