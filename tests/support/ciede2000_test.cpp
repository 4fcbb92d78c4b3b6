// ciede2000.h against Sharma, Wu & Dalal 2005, Table 1 (all 34 pairs, to their four decimals),
// and the sRGB → CIELAB conversion against values any colour calculator gives.

#include "tests/support/ciede2000.h"

#include <gtest/gtest.h>

#include <array>

namespace vegstream::testing {
namespace {

// Sharma, Wu & Dalal 2005, Table 1: L1 a1 b1, L2 a2 b2, ΔE00.
constexpr std::array<std::array<double, 7>, 34> kSharmaPairs{{
    {50.0000, 2.6772, -79.7751, 50.0000, 0.0000, -82.7485, 2.0425},
    {50.0000, 3.1571, -77.2803, 50.0000, 0.0000, -82.7485, 2.8615},
    {50.0000, 2.8361, -74.0200, 50.0000, 0.0000, -82.7485, 3.4412},
    {50.0000, -1.3802, -84.2814, 50.0000, 0.0000, -82.7485, 1.0000},
    {50.0000, -1.1848, -84.8006, 50.0000, 0.0000, -82.7485, 1.0000},
    {50.0000, -0.9009, -85.5211, 50.0000, 0.0000, -82.7485, 1.0000},
    {50.0000, 0.0000, 0.0000, 50.0000, -1.0000, 2.0000, 2.3669},
    {50.0000, -1.0000, 2.0000, 50.0000, 0.0000, 0.0000, 2.3669},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0009, 7.1792},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0010, 7.1792},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0011, 7.2195},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0012, 7.2195},
    {50.0000, -0.0010, 2.4900, 50.0000, 0.0009, -2.4900, 4.8045},
    {50.0000, -0.0010, 2.4900, 50.0000, 0.0010, -2.4900, 4.8045},
    {50.0000, -0.0010, 2.4900, 50.0000, 0.0011, -2.4900, 4.7461},
    {50.0000, 2.5000, 0.0000, 50.0000, 0.0000, -2.5000, 4.3065},
    {50.0000, 2.5000, 0.0000, 73.0000, 25.0000, -18.0000, 27.1492},
    {50.0000, 2.5000, 0.0000, 61.0000, -5.0000, 29.0000, 22.8977},
    {50.0000, 2.5000, 0.0000, 56.0000, -27.0000, -3.0000, 31.9030},
    {50.0000, 2.5000, 0.0000, 58.0000, 24.0000, 15.0000, 19.4535},
    {50.0000, 2.5000, 0.0000, 50.0000, 3.1736, 0.5854, 1.0000},
    {50.0000, 2.5000, 0.0000, 50.0000, 3.2972, 0.0000, 1.0000},
    {50.0000, 2.5000, 0.0000, 50.0000, 1.8634, 0.5757, 1.0000},
    {50.0000, 2.5000, 0.0000, 50.0000, 3.2592, 0.3350, 1.0000},
    {60.2574, -34.0099, 36.2677, 60.4626, -34.1751, 39.4387, 1.2644},
    {63.0109, -31.0961, -5.8663, 62.8187, -29.7946, -4.0864, 1.2630},
    {61.2901, 3.7196, -5.3901, 61.4292, 2.2480, -4.9620, 1.8731},
    {35.0831, -44.1164, 3.7933, 35.0232, -40.0716, 1.5901, 1.8645},
    {22.7233, 20.0904, -46.6940, 23.0331, 14.9730, -42.5619, 2.0373},
    {36.4612, 47.8580, 18.3852, 36.2715, 50.5065, 21.2231, 1.4146},
    {90.8027, -2.0831, 1.4410, 91.1528, -1.6435, 0.0447, 1.4441},
    {90.9257, -0.5406, -0.9208, 88.6381, -0.8985, -0.7239, 1.5381},
    {6.7747, -0.2908, -2.4247, 5.8714, -0.0985, -2.2286, 0.6377},
    {2.0776, 0.0795, -1.1350, 0.9033, -0.0636, -0.5514, 0.9082},
}};

TEST(Ciede2000, MatchesSharmasPublishedPairsBothWays) {
  for (size_t i = 0; i < kSharmaPairs.size(); ++i) {
    const auto& p = kSharmaPairs[i];
    const Lab x{p[0], p[1], p[2]}, y{p[3], p[4], p[5]};
    EXPECT_NEAR(ciede2000(x, y), p[6], 1e-4) << "pair " << i + 1;
    EXPECT_NEAR(ciede2000(y, x), p[6], 1e-4) << "pair " << i + 1 << " swapped";
  }
}

TEST(Ciede2000, IsZeroForEqualColours) {
  EXPECT_DOUBLE_EQ(ciede2000({42.0, -12.0, 30.0}, {42.0, -12.0, 30.0}), 0.0);
  EXPECT_DOUBLE_EQ(ciede2000({0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}), 0.0);
}

TEST(SrgbToLab, WhiteGreyAndPrimariesAreTheStandardsValues) {
  const Lab white = labFromSrgb8(255, 255, 255);
  EXPECT_NEAR(white.L, 100.0, 1e-3);
  EXPECT_NEAR(white.a, 0.0, 0.01);
  EXPECT_NEAR(white.b, 0.0, 0.01);
  const Lab black = labFromSrgb8(0, 0, 0);
  EXPECT_NEAR(black.L, 0.0, 1e-9);
  // sRGB 119 encodes 18.4 % linear: L* 50.0 (the middle grey of CIELAB).
  EXPECT_NEAR(labFromSrgb8(119, 119, 119).L, 50.0, 0.2);
  const Lab red = labFromSrgb8(255, 0, 0);  // (53.24, 80.09, 67.20) in every D65 calculator
  EXPECT_NEAR(red.L, 53.24, 0.05);
  EXPECT_NEAR(red.a, 80.09, 0.1);
  EXPECT_NEAR(red.b, 67.20, 0.1);
  const Lab blue = labFromSrgb8(0, 0, 255);  // (32.30, 79.19, −107.86)
  EXPECT_NEAR(blue.L, 32.30, 0.05);
  EXPECT_NEAR(blue.a, 79.19, 0.1);
  EXPECT_NEAR(blue.b, -107.86, 0.1);
}

TEST(SrgbToLab, LinearAndEncodedAgree) {
  const double lin = srgbToLinear(128 / 255.0);
  EXPECT_NEAR(lin, 0.2158605, 1e-6);
  EXPECT_NEAR(linearToSrgb(lin) * 255.0, 128.0, 1e-9);
  const Lab a = labFromSrgb8(74, 68, 50), b = labFromLinear(glm::vec3(static_cast<float>(srgbToLinear(74 / 255.0)),
                                                                      static_cast<float>(srgbToLinear(68 / 255.0)),
                                                                      static_cast<float>(srgbToLinear(50 / 255.0))));
  EXPECT_LT(ciede2000(a, b), 1e-3);
}

}  // namespace
}  // namespace vegstream::testing
