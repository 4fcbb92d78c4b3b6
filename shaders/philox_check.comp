#version 450
#extension GL_GOOGLE_include_directive : require
// Test kernel, not a pass: evaluates common/philox.glsl (Philox-2×32, core seed
// ../shared/seeds/001_3eca9f2c7752e4fb.txt §2.2) for `count` inputs made from the index, so
// tests/render/philox_gpu_test.cpp can compare every word with vegetation/philox.h. Per index i:
// ctr = (i, i · 0x85EBCA6B ^ 0xC2B2AE35), key = i · 0x27D4EB2F + 0x165667B1 (the test makes the
// same); out[6i .. 6i+5] = philox2x32_3, philox2x32(…, 7), philox2x32(…, 10).
#include "philox.glsl"
layout(local_size_x = 64) in;
layout(set = 0, binding = 0, std430) writeonly buffer Outputs {
  uint words[];
} outputs;
layout(push_constant) uniform Push {
  uint count;
} push;
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= push.count) return;
  uvec2 ctr = uvec2(i, (i * 0x85EBCA6Bu) ^ 0xC2B2AE35u);
  uint key = i * 0x27D4EB2Fu + 0x165667B1u;
  uvec2 r3 = philox2x32_3(ctr, key), r7 = philox2x32(ctr, key, 7), r10 = philox2x32(ctr, key, 10);
  outputs.words[6u * i + 0u] = r3.x;
  outputs.words[6u * i + 1u] = r3.y;
  outputs.words[6u * i + 2u] = r7.x;
  outputs.words[6u * i + 3u] = r7.y;
  outputs.words[6u * i + 4u] = r10.x;
  outputs.words[6u * i + 5u] = r10.y;
}
