// vegetation/philox.h: Philox-2×32 (core seed ../shared/seeds/001_3eca9f2c7752e4fb.txt §2.2)
// against Random123's known answers, and u01's range and mean.
//
// Known answers: the philox2x32 lines of Random123's examples/kat_vectors (zeros, all ones, pi
// digits; format "R ctr0 ctr1 key → out0 out1"), as cut-and-pasted into D. E. Shaw Research's
// fs123 (core123/ut/ut_philox.cpp) — the same lines appear in other ports. The key = 1 lines
// come from the generated kat_vectors of the Random123 manual (girving/random123-manual,
// examples/kat_vectors); Boost.Random's philox test checks one of them too.

#include "vegetation/philox.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <gtest/gtest.h>

namespace vegstream::vegetation {
namespace {

struct Kat {
  uint32_t ctr0, ctr1, key, out0, out1;
};

// The functions are constexpr: a known answer checked at compile time.
static_assert(philox2x32<10>(0x243f6a88u, 0x85a308d3u, 0x13198a2eu).x == 0xdd7ce038u);
static_assert(philox2x32<10>(0x243f6a88u, 0x85a308d3u, 0x13198a2eu).y == 0xf62a4c12u);
static_assert(philox(1u, 2u, 3u).x == philox2x32<3>(1u, 2u, 3u).x);
static_assert(u01(0u) == 0.0f && u01(0xffffffffu) < 1.0f);

constexpr Kat kKat7[] = {
    {0x00000000u, 0x00000000u, 0x00000000u, 0x257a3673u, 0xcd26be2au},
    {0xffffffffu, 0xffffffffu, 0xffffffffu, 0xab302c4du, 0x3dc9d239u},
    {0x243f6a88u, 0x85a308d3u, 0x13198a2eu, 0xbedbbe6bu, 0xe4c770b3u},
    {0x00000001u, 0x00000000u, 0x00000001u, 0xdd304d50u, 0x12e4d653u},
    {0x243f6a88u, 0x85a308d3u, 0x00000001u, 0x5e8c7db7u, 0xfe555fa5u},
};
constexpr Kat kKat10[] = {
    {0x00000000u, 0x00000000u, 0x00000000u, 0xff1dae59u, 0x6cd10df2u},
    {0xffffffffu, 0xffffffffu, 0xffffffffu, 0x2c3f628bu, 0xab4fd7adu},
    {0x243f6a88u, 0x85a308d3u, 0x13198a2eu, 0xdd7ce038u, 0xf62a4c12u},
    {0x00000001u, 0x00000000u, 0x00000001u, 0xdf873210u, 0xf52df537u},
    {0x243f6a88u, 0x85a308d3u, 0x00000001u, 0x249cdc9cu, 0x4f745808u},
};

TEST(Philox, SevenRoundsMatchRandom123KnownAnswers) {
  for (const Kat& k : kKat7) {
    const Philox2x32Out o = philox2x32<7>(k.ctr0, k.ctr1, k.key);
    EXPECT_EQ(o.x, k.out0) << std::hex << k.ctr0 << " " << k.ctr1 << " " << k.key;
    EXPECT_EQ(o.y, k.out1) << std::hex << k.ctr0 << " " << k.ctr1 << " " << k.key;
  }
}

TEST(Philox, TenRoundsMatchRandom123KnownAnswers) {
  for (const Kat& k : kKat10) {
    const Philox2x32Out o = philox2x32<10>(k.ctr0, k.ctr1, k.key);
    EXPECT_EQ(o.x, k.out0) << std::hex << k.ctr0 << " " << k.ctr1 << " " << k.key;
    EXPECT_EQ(o.y, k.out1) << std::hex << k.ctr0 << " " << k.ctr1 << " " << k.key;
  }
}

TEST(Philox, ThreeRoundsAreTheSeedsDefault) {
  EXPECT_EQ(kPhiloxRounds, 3);
  const Philox2x32Out a = philox(7u, 11u, 13u), b = philox2x32<3>(7u, 11u, 13u);
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.y, b.y);
  // Different counters and keys give different words (a smoke test of the mixing).
  EXPECT_NE(philox(0u, 0u, 0u).x, philox(1u, 0u, 0u).x);
  EXPECT_NE(philox(0u, 0u, 0u).x, philox(0u, 0u, 1u).x);
}

TEST(Philox, U01IsExactAndInRange) {
  EXPECT_EQ(u01(0u), 0.0f);
  EXPECT_EQ(u01(0xffffffffu), 1.0f - 1.0f / 16777216.0f);  // the largest float below 1
  EXPECT_EQ(u01(0x80000000u), 0.5f);
  EXPECT_EQ(u01(0x000000ffu), 0.0f);  // the low 8 bits are dropped
}

// 10⁶ draws z = u01(philox(i, 0, key)): all in [0, 1), mean within 3σ of 1/2 (σ of the mean =
// sqrt(1/12 / n)), and each tenth of [0, 1) holds n/10 within 4σ of a binomial.
TEST(Philox, U01OfConsecutiveCountersIsUniform) {
  constexpr int n = 1000000;
  double sum = 0.0;
  int bins[10] = {};
  float lo = 1.0f, hi = 0.0f;
  for (int i = 0; i < n; ++i) {
    const Philox2x32Out o = philox(static_cast<uint32_t>(i), 0u, 0x5eed1234u);
    const float z = u01(o.x);
    lo = std::min(lo, z);
    hi = std::max(hi, z);
    sum += z;
    ++bins[std::min(9, static_cast<int>(z * 10.0f))];
  }
  EXPECT_GE(lo, 0.0f);
  EXPECT_LT(hi, 1.0f);
  const double mean = sum / n, sigma = std::sqrt(1.0 / 12.0 / n);
  EXPECT_NEAR(mean, 0.5, 3.0 * sigma);
  const double binSigma = std::sqrt(n * 0.1 * 0.9);
  for (int b = 0; b < 10; ++b) EXPECT_NEAR(bins[b], n / 10, 4.0 * binSigma) << "bin " << b;
}

}  // namespace
}  // namespace vegstream::vegetation
