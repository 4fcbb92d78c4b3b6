// Philox-2×32-R (Salmon et al. 2011, Random123), the GLSL twin of vegetation/philox.h: core
// seed ../shared/seeds/001_3eca9f2c7752e4fb.txt §2.2 hashes each plant with Philox-2×32-3.
// Bit-identical to the C++ (tests/render/philox_gpu_test.cpp): umulExtended gives the same
// 64-bit product as the C++ mulhilo, uint arithmetic wraps the same way.
#ifndef PHILOX_GLSL
#define PHILOX_GLSL

const uint kPhiloxM2x32 = 0xD256D193u;  // Random123 PHILOX_M2x32_0
const uint kPhiloxW32 = 0x9E3779B9u;    // Random123 PHILOX_W32_0

// One round: hi, lo = mulhilo(M, ctr.x); ctr = (hi ^ key ^ ctr.y, lo).
uvec2 philoxRound(uvec2 ctr, uint key) {
  uint hi, lo;
  umulExtended(kPhiloxM2x32, ctr.x, hi, lo);
  return uvec2(hi ^ key ^ ctr.y, lo);
}

// `rounds` rounds; the key is bumped by the Weyl constant between rounds, not before the first.
uvec2 philox2x32(uvec2 ctr, uint key, int rounds) {
  for (int r = 0; r < rounds; ++r) {
    if (r > 0) key += kPhiloxW32;
    ctr = philoxRound(ctr, key);
  }
  return ctr;
}

// The seed's Philox-2×32-3, unrolled.
uvec2 philox2x32_3(uvec2 ctr, uint key) {
  ctr = philoxRound(ctr, key);
  ctr = philoxRound(ctr, key + kPhiloxW32);
  return philoxRound(ctr, key + 2u * kPhiloxW32);
}

// Uniform float in [0, 1): the top 24 bits times 2⁻²⁴, exact in float (as vegetation::u01).
float philoxU01(uint x) { return float(x >> 8) * (1.0 / 16777216.0); }

#endif  // PHILOX_GLSL
