#pragma once
// Philox-2×32-R, the counter-based random number generator of Salmon, Moraes, Dror and Shaw,
// "Parallel random numbers: as easy as 1, 2, 3" (SC 2011; the Random123 library's philox.h).
// Core seed ../shared/seeds/001_3eca9f2c7752e4fb.txt §2.2 hashes each plant's (triangle, index)
// with Philox-2×32-3: a pure function of counter and key, so a plant's random numbers depend on
// nothing but its identity (view-independent placement) and the GPU can recompute them.
//
// One round (Random123's philox2x32round): hi·2³² + lo = 0xD256D193 · ctr0 (mulhilo),
// ctr = {hi ^ key ^ ctr1, lo}; between rounds the key is bumped by the Weyl constant 0x9E3779B9
// (Random123's philox2x32bumpkey), so round r uses key + (r − 1) · 0x9E3779B9. Only 32-bit
// unsigned arithmetic (wrapping): shaders/common/philox.glsl does the same with umulExtended
// and gives the same bits (tests/render/philox_gpu_test.cpp checks 10⁶ inputs).
// tests/vegetation/philox_test.cpp checks Random123's known-answer vectors (7 and 10 rounds).

#include <cstdint>

namespace vegstream::vegetation {

struct Philox2x32Out {
  uint32_t x, y;
};

inline constexpr uint32_t kPhiloxM2x32 = 0xD256D193u;  // Random123 PHILOX_M2x32_0
inline constexpr uint32_t kPhiloxW32 = 0x9E3779B9u;    // Random123 PHILOX_W32_0 (golden ratio)

// Philox-2×32 with `Rounds` rounds of counter (ctr0, ctr1) under `key`.
template <int Rounds>
constexpr Philox2x32Out philox2x32(uint32_t ctr0, uint32_t ctr1, uint32_t key) {
  static_assert(Rounds >= 1 && Rounds <= 16, "Random123 defines 1 … 16 rounds");
  for (int r = 0; r < Rounds; ++r) {
    if (r > 0) key += kPhiloxW32;  // bump between rounds, not before the first
    const uint64_t product = uint64_t{kPhiloxM2x32} * ctr0;
    const auto hi = static_cast<uint32_t>(product >> 32);
    const auto lo = static_cast<uint32_t>(product);
    ctr0 = hi ^ key ^ ctr1;
    ctr1 = lo;
  }
  return {ctr0, ctr1};
}

// The seed's Philox-2×32-3 (§2.2): three rounds are enough for plant placement and cheap on
// the GPU (Random123 recommends 10 for general use, 7 is the least that passes BigCrush).
inline constexpr int kPhiloxRounds = 3;

constexpr Philox2x32Out philox(uint32_t ctr0, uint32_t ctr1, uint32_t key) {
  return philox2x32<kPhiloxRounds>(ctr0, ctr1, key);
}

// Uniform float in [0, 1): the top 24 bits times 2⁻²⁴. 24 bits fit a float's mantissa, so the
// conversion and the product are exact on CPU and GPU alike (no rounding up to 1.0).
constexpr float u01(uint32_t x) { return static_cast<float>(x >> 8) * (1.0f / 16777216.0f); }

}  // namespace vegstream::vegetation
