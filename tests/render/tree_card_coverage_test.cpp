// The cards' coverage texture (render/tree_card_coverage.h), baked on the CPU from the shared
// outline (shaders/common/tree_card_shape.glsl): each level the box filter of the outline at its
// needle detail, the conifer's needles resolved at level 0 and their mean at the coarsest, nothing
// outside the card's trapezoid, the same bytes every bake. No GPU.
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "render/tree_card_coverage.h"

namespace vegstream::render {
namespace {

constexpr uint32_t kConifer = 0, kBroadleaf = 1;

float texel(const std::vector<float>& level, uint32_t size, float u, float v) {
  const auto x = std::min(static_cast<uint32_t>(u * static_cast<float>(size)), size - 1);
  const auto y = std::min(static_cast<uint32_t>(v * static_cast<float>(size)), size - 1);
  return level[size_t{y} * size + x];
}

TEST(TreeCardCoverage, LevelsHaveTheirSizesAndTheNeedlesFadeWithTheLevel) {
  for (uint32_t layer = 0; layer < kTreeCardLayers; ++layer) {
    const auto levels = bakeTreeCardLayer(layer);
    ASSERT_EQ(levels.size(), kTreeCardLevels);
    for (uint32_t l = 0; l < kTreeCardLevels; ++l) {
      EXPECT_EQ(levels[l].size(), size_t{kTreeCardSize >> l} * (kTreeCardSize >> l));
      for (float c : levels[l]) ASSERT_TRUE(c >= 0.0f && c <= 1.0f) << "layer " << layer << " level " << l;
    }
  }
  EXPECT_EQ(treeCardLevelDetail(0), 1.0f);  // drawn where a texel is a quarter pixel of a near card
  EXPECT_EQ(treeCardLevelDetail(kTreeCardLevels - 1), 0.0f);
  for (uint32_t l = 1; l < kTreeCardLevels; ++l) EXPECT_LE(treeCardLevelDetail(l), treeCardLevelDetail(l - 1));
}

TEST(TreeCardCoverage, ConiferLevelZeroResolvesTheNeedlesInsideTheTrapezoidOnly) {
  const auto levels = bakeTreeCardLayer(kConifer);
  const std::vector<float>& l0 = levels[0];
  int outside = 0, gaps = 0, needles = 0, inNeedleZone = 0, near = 0;
  double insideSum = 0.0;
  int insideCount = 0;
  for (uint32_t y = 0; y < kTreeCardSize; ++y)
    for (uint32_t x = 0; x < kTreeCardSize; ++x) {
      const float u = (static_cast<float>(x) + 0.5f) / kTreeCardSize,
                  v = (static_cast<float>(y) + 0.5f) / kTreeCardSize;
      const float across = std::abs(u - 0.5f) * 2.0f, width = 1.0f - 0.4f * v;
      const float c = l0[size_t{y} * kTreeCardSize + x];
      if (across > width + 0.02f) {
        ++outside;
        EXPECT_EQ(c, 0.0f) << "u " << u << " v " << v;
      } else if (across < width - 0.1f && v > 0.15f) {
        insideSum += c;
        ++insideCount;
      }
      if (across > 0.2f && across < 0.45f && v > 0.2f && v < 0.8f) {
        ++inNeedleZone;
        gaps += c < 0.1f;
        needles += c > 0.9f;
      }
      // Each texel is the mean of its square's points: close to the outline at its centre
      // wherever the outline is smooth there.
      near += std::abs(c - treeCardOutline(kConifer, u, v, 1.0f)) < 0.2f;
    }
  EXPECT_GT(outside, 0);
  const double mean = insideSum / insideCount;
  std::printf("conifer level 0: mean %.3f inside, needle zone %d texels: %d gaps, %d needles\n", mean, inNeedleZone,
              gaps, needles);
  EXPECT_GT(mean, 0.45);  // the needles' share, the twig and their lean
  EXPECT_LT(mean, 0.8);
  EXPECT_GT(gaps, inNeedleZone / 10);    // open between the needles …
  EXPECT_GT(needles, inNeedleZone / 4);  // … and covered along them
  EXPECT_GT(near, static_cast<int>(0.95 * kTreeCardSize * kTreeCardSize));
  // The twig along the middle is covered from the stem's fade-in to the tip.
  for (float v = 0.12f; v < 0.98f; v += 0.05f) EXPECT_GT(texel(l0, kTreeCardSize, 0.5f, v), 0.9f) << "v " << v;
}

TEST(TreeCardCoverage, ConiferCoarsestLevelHoldsTheNeedlesMean) {
  const auto levels = bakeTreeCardLayer(kConifer);
  const uint32_t size = kTreeCardSize >> (kTreeCardLevels - 1);
  const std::vector<float>& last = levels.back();
  // The texels wholly inside the trapezoid (near the middle, clear of the stem's fade-in).
  for (float v : {0.4f, 0.6f})
    for (float u : {0.4f, 0.6f}) {
      const float c = texel(last, size, u, v);
      EXPECT_GT(c, 0.75f) << "u " << u << " v " << v;
      EXPECT_LT(c, 0.9f) << "u " << u << " v " << v;
    }
  // The mean coverage grows from the resolved needles towards their (higher) mean.
  const auto mean = [](const std::vector<float>& l) {
    double s = 0.0;
    for (float c : l) s += c;
    return s / static_cast<double>(l.size());
  };
  EXPECT_GT(mean(levels.back()), mean(levels.front()) + 0.05);
}

TEST(TreeCardCoverage, BroadleafLevelsAreBoxFiltersOfTheClump) {
  const auto levels = bakeTreeCardLayer(kBroadleaf);
  // A leaf's middle is covered; the card's corners are not.
  EXPECT_GT(texel(levels[0], kTreeCardSize, 0.5f + 0.2f * std::cos(1.0f), 0.5f + 0.2f * std::sin(1.0f)), 0.95f);
  for (float u : {0.01f, 0.99f})
    for (float v : {0.01f, 0.99f}) EXPECT_EQ(texel(levels[0], kTreeCardSize, u, v), 0.0f);
  for (uint32_t l = 1; l < kTreeCardLevels; ++l) {
    const uint32_t size = kTreeCardSize >> l, above = size * 2;
    for (uint32_t y = 0; y < size; ++y)
      for (uint32_t x = 0; x < size; ++x) {
        const size_t a = size_t{2} * y * above + size_t{2} * x;
        const float box =
            0.25f * (levels[l - 1][a] + levels[l - 1][a + 1] + levels[l - 1][a + above] + levels[l - 1][a + above + 1]);
        ASSERT_NEAR(levels[l][size_t{y} * size + x], box, 1e-5f) << "level " << l;
      }
  }
}

TEST(TreeCardCoverage, SameBakeEveryTime) {
  for (uint32_t layer = 0; layer < kTreeCardLayers; ++layer)
    EXPECT_EQ(bakeTreeCardLayer(layer), bakeTreeCardLayer(layer));
}

}  // namespace
}  // namespace vegstream::render
