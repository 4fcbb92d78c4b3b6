// Colour scores (core seed 001 §3.3 eq. 16) against hand computations.

#include "vegetation/colour_score.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

namespace vegstream::vegetation {
namespace {

void expectHsv(glm::vec3 got, glm::vec3 want) {
  EXPECT_NEAR(got.x, want.x, 1e-6f);
  EXPECT_NEAR(got.y, want.y, 1e-6f);
  EXPECT_NEAR(got.z, want.z, 1e-6f);
}

TEST(ColourScore, SrgbFromHsvInvertsHsvFromSrgb) {
  EXPECT_EQ(srgbFromHsv({0, 1, 1}), glm::vec3(1, 0, 0));
  EXPECT_EQ(srgbFromHsv({0, 0, 0.5f}), glm::vec3(0.5f));
  for (float r = 0.0f; r <= 1.0f; r += 0.125f)
    for (float g = 0.0f; g <= 1.0f; g += 0.125f)
      for (float b = 0.0f; b <= 1.0f; b += 0.125f) {
        const glm::vec3 back = srgbFromHsv(hsvFromSrgb({r, g, b}));
        EXPECT_NEAR(back.r, r, 1e-5f);
        EXPECT_NEAR(back.g, g, 1e-5f);
        EXPECT_NEAR(back.b, b, 1e-5f);
      }
}

TEST(ColourScore, HsvOfPrimariesGreysAndMixtures) {
  expectHsv(hsvFromSrgb({1, 0, 0}), {0, 1, 1});
  expectHsv(hsvFromSrgb({1, 1, 0}), {1.0f / 6, 1, 1});
  expectHsv(hsvFromSrgb({0, 1, 0}), {1.0f / 3, 1, 1});
  expectHsv(hsvFromSrgb({0, 0, 1}), {2.0f / 3, 1, 1});
  expectHsv(hsvFromSrgb({0.5f, 0.5f, 0.5f}), {0, 0, 0.5f});  // grey: hue 0 by convention
  expectHsv(hsvFromSrgb({0, 0, 0}), {0, 0, 0});
  // Red-dominant with blue above green: hue below 0 wraps to just under 1.
  expectHsv(hsvFromSrgb({1, 0, 0.5f}), {1.0f - 1.0f / 12, 1, 1});
  // g max 0.4, min 0.2: h = (2 + (0.3 − 0.2) / 0.2) / 6, s = 0.2 / 0.4.
  expectHsv(hsvFromSrgb({0.2f, 0.4f, 0.3f}), {2.5f / 6, 0.5f, 0.4f});
  expectHsv(hsvFromSrgb8(255, 0, 0), {0, 1, 1});
  // Hue stays in [0, 1) even where −tiny + 1 would round to 1.
  const glm::vec3 h = hsvFromSrgb({1.0f, 0.0f, 1e-8f});
  EXPECT_GE(h.x, 0.0f);
  EXPECT_LT(h.x, 1.0f);
}

TEST(ColourScore, SrgbTransferAndHsvOfLinearColours) {
  EXPECT_EQ(srgbEncode(0.0f), 0.0f);
  EXPECT_NEAR(srgbEncode(1.0f), 1.0f, 1e-6f);
  EXPECT_NEAR(srgbDecode(0.5f), 0.214041f, 1e-5f);
  EXPECT_NEAR(srgbEncode(0.002f), 0.002f * 12.92f, 1e-7f);  // the linear toe
  for (float c = 0.0f; c <= 1.0f; c += 0.05f) EXPECT_NEAR(srgbEncode(srgbDecode(c)), c, 2e-6f);
  const glm::vec3 srgb{0.42f, 0.47f, 0.24f};
  const glm::vec3 linear{srgbDecode(srgb.r), srgbDecode(srgb.g), srgbDecode(srgb.b)};
  const glm::vec3 a = hsvFromSrgb(srgb), b = hsvFromLinear(linear);
  EXPECT_NEAR(a.x, b.x, 1e-5f);
  EXPECT_NEAR(a.y, b.y, 1e-5f);
  EXPECT_NEAR(a.z, b.z, 1e-5f);
}

TEST(ColourScore, HueDistanceWrapsAroundTheCircle) {
  EXPECT_NEAR(hueDistance(0.95f, 0.05f), 0.1f, 1e-6f);
  EXPECT_NEAR(hueDistance(0.05f, 0.95f), 0.1f, 1e-6f);
  EXPECT_NEAR(hueDistance(0.3f, 0.1f), 0.2f, 1e-6f);
  EXPECT_NEAR(hueDistance(0.2f, 0.7f), 0.5f, 1e-6f);  // opposite hues: the largest distance
  EXPECT_NEAR(hueDistance(0.0f, 1.0f), 0.0f, 1e-6f);
}

TEST(ColourScore, WeightsScaleEachChannel) {
  const glm::vec3 a{0.95f, 0.5f, 0.5f}, b{0.05f, 0.2f, 0.1f};  // Δ = (0.1 wrapped, 0.3, 0.4)
  EXPECT_NEAR(weightedHsvDistance(a, b, {1, 1, 1}), std::sqrt(0.01f + 0.09f + 0.16f), 1e-6f);
  EXPECT_NEAR(weightedHsvDistance(a, b, {2, 0, 0}), 0.2f, 1e-6f);
  EXPECT_NEAR(weightedHsvDistance(a, b, {0, 1, 0}), 0.3f, 1e-6f);
  EXPECT_NEAR(weightedHsvDistance(a, b, {0, 0, 0.5f}), 0.2f, 1e-6f);
  // Hue weight 0 (grey rock): the hue of the base colour does not matter.
  EXPECT_EQ(weightedHsvDistance({0.0f, 0.1f, 0.5f}, {0.6f, 0.1f, 0.5f}, {0, 1, 1}), 0.0f);
}

TEST(ColourScore, ScoreIsTheInverseDistanceToThePowerP) {
  ColourScoreParams params{{0.3f, 0.5f, 0.5f}, {1, 1, 1}, 2.0f};
  const glm::vec3 base{0.3f, 0.8f, 0.9f};  // distance √(0.3² + 0.4²) = 0.5
  EXPECT_NEAR(colourScore(params, base), 4.0f, 1e-5f);
  params.p = 3.0f;
  EXPECT_NEAR(colourScore(params, base), 8.0f, 1e-5f);
  params.p = 1.0f;
  EXPECT_NEAR(colourScore(params, base), 2.0f, 1e-5f);
  EXPECT_NEAR(logColourScore(params, base), std::log(2.0f), 1e-6f);
  // An exact match is clamped to kMinColourDistance: large and finite.
  params.p = 2.0f;
  const float exact = colourScore(params, params.reference);
  EXPECT_TRUE(std::isfinite(exact));
  EXPECT_NEAR(exact, 1.0f / (kMinColourDistance * kMinColourDistance), 1e8f * 1e-4f);
}

TEST(ColourScore, AColourHalfwayBetweenTwoReferencesBlendsEvenly) {
  const std::vector<ColourScoreParams> types{{{0.2f, 0.5f, 0.5f}, {1, 1, 1}, 3.0f},
                                             {{0.4f, 0.5f, 0.5f}, {1, 1, 1}, 3.0f}};
  auto w = blendWeights(types, {0.3f, 0.5f, 0.5f});
  EXPECT_NEAR(w[0], 0.5f, 1e-6f);
  EXPECT_NEAR(w[1], 0.5f, 1e-6f);
  // Across the red end of the circle: 0.95 and 0.15 are both 0.1 from 0.05.
  const std::vector<ColourScoreParams> wrapped{{{0.95f, 0.5f, 0.5f}, {1, 1, 1}, 3.0f},
                                               {{0.15f, 0.5f, 0.5f}, {1, 1, 1}, 3.0f}};
  w = blendWeights(wrapped, {0.05f, 0.5f, 0.5f});
  EXPECT_NEAR(w[0], 0.5f, 1e-5f);
  EXPECT_NEAR(w[1], 0.5f, 1e-5f);
}

TEST(ColourScore, BlendWeightsAreScoresOverTheirSum) {
  // Saturation only: distances 0.2 and 0.4 from s = 0.4.
  std::vector<ColourScoreParams> types{{{0.0f, 0.2f, 0.0f}, {0, 1, 0}, 2.0f}, {{0.0f, 0.8f, 0.0f}, {0, 1, 0}, 2.0f}};
  const glm::vec3 base{0.7f, 0.4f, 0.9f};
  auto w = blendWeights(types, base);  // 25 / (25 + 6.25)
  EXPECT_NEAR(w[0], 0.8f, 1e-6f);
  EXPECT_NEAR(w[1], 0.2f, 1e-6f);
  // A larger p sharpens the transition: 2⁴ / (2⁴ + 1); a smaller one softens it.
  for (auto& t : types) t.p = 4.0f;
  EXPECT_NEAR(blendWeights(types, base)[0], 16.0f / 17.0f, 1e-6f);
  for (auto& t : types) t.p = 1.0f;
  EXPECT_NEAR(blendWeights(types, base)[0], 2.0f / 3.0f, 1e-6f);
  // Each type has its own exponent: s = 5 and 6.25.
  types[1].p = 2.0f;
  EXPECT_NEAR(blendWeights(types, base)[0], 5.0f / 11.25f, 1e-6f);
  EXPECT_EQ(bestMatch(types, base), 1u);
}

TEST(ColourScore, ExactMatchesAndHugeExponentsStayFinite) {
  std::vector<ColourScoreParams> types{{{0.3f, 0.5f, 0.5f}, {1, 1, 1}, 2.0f}, {{0.3f, 0.9f, 0.5f}, {1, 1, 1}, 2.0f}};
  auto w = blendWeights(types, types[0].reference);  // s = 1e8 against 6.25
  EXPECT_NEAR(w[0], 1.0f, 1e-6f);
  EXPECT_GT(w[1], 0.0f);
  EXPECT_NEAR(w[0] + w[1], 1.0f, 1e-6f);
  types[1].reference = types[0].reference;  // two types on the same colour share it evenly
  w = blendWeights(types, types[0].reference);
  EXPECT_NEAR(w[0], 0.5f, 1e-6f);
  // p = 40: 0.1^−40 = 1e40 overflows a float, the weights do not.
  std::vector<ColourScoreParams> sharp{{{0.0f, 0.2f, 0.0f}, {0, 1, 0}, 40.0f}, {{0.0f, 0.4f, 0.0f}, {0, 1, 0}, 40.0f}};
  EXPECT_FALSE(std::isfinite(colourScore(sharp[0], {0.0f, 0.3f, 0.0f})));
  w = blendWeights(sharp, {0.0f, 0.35f, 0.0f});  // distances 0.15 and 0.05: (1/3)^40
  EXPECT_TRUE(std::isfinite(w[0]) && std::isfinite(w[1]));
  EXPECT_NEAR(w[1], 1.0f, 1e-6f);
  EXPECT_NEAR(w[0], std::pow(1.0f / 3.0f, 40.0f), 1e-20f);
  EXPECT_TRUE(blendWeights(std::vector<ColourScoreParams>{}, {0, 0, 0}).empty());
}

}  // namespace
}  // namespace vegstream::vegetation
