// The procedural detail patterns and the terrain-detail uniform block, on the CPU (no GPU).

#include "render/detail_patterns.h"

#include <cmath>
#include <cstdlib>

#include <gtest/gtest.h>

#include "render/terrain_detail.h"

namespace vegstream::render {
namespace {

using vegetation::DetailSurface;
constexpr uint32_t kSize = 128;

double channelMean(const std::vector<uint8_t>& rgba, size_t c) {
  double sum = 0.0;
  for (size_t i = c; i < rgba.size(); i += 4) sum += rgba[i];
  return sum / static_cast<double>(rgba.size() / 4) / 255.0;
}

// Mean absolute difference of luminance between horizontally (dx = 1) or vertically adjacent
// texels, over the columns / rows from `from` to `from + 1` (wrapping).
double stepAcross(const std::vector<uint8_t>& rgba, uint32_t size, uint32_t from, bool horizontal) {
  double sum = 0.0;
  for (uint32_t k = 0; k < size; ++k) {
    const uint32_t a = from, b = (from + 1) % size;
    const size_t ia = horizontal ? (size_t{k} * size + a) : (size_t{a} * size + k);
    const size_t ib = horizontal ? (size_t{k} * size + b) : (size_t{b} * size + k);
    sum += std::abs(int(rgba[ia * 4 + 1]) - int(rgba[ib * 4 + 1]));
  }
  return sum / size;
}

TEST(DetailPatterns, AreDeterministicNeutralOnAverageAndDistinct) {
  std::vector<std::vector<uint8_t>> layers;
  for (uint32_t s = 0; s < vegetation::kDetailSurfaceCount; ++s) {
    const auto surface = static_cast<DetailSurface>(s);
    const auto a = generateDetailPattern(surface, kSize);
    ASSERT_EQ(a.size(), size_t{kSize} * kSize * 4);
    EXPECT_EQ(a, generateDetailPattern(surface, kSize)) << "surface " << s;
    for (size_t c = 0; c < 3; ++c) EXPECT_NEAR(channelMean(a, c), 0.5, 0.02) << "surface " << s << " channel " << c;
    // Real contrast: a standard deviation of several grey levels.
    double var = 0.0;
    for (size_t i = 1; i < a.size(); i += 4) var += (a[i] / 255.0 - 0.5) * (a[i] / 255.0 - 0.5);
    EXPECT_GT(std::sqrt(var / static_cast<double>(a.size() / 4)), 0.06) << "surface " << s;
    for (size_t i = 3; i < a.size(); i += 4) ASSERT_EQ(a[i], 255);
    layers.push_back(a);
  }
  for (size_t i = 0; i < layers.size(); ++i)
    for (size_t j = i + 1; j < layers.size(); ++j) EXPECT_NE(layers[i], layers[j]);
}

// Seamless tiling: the step from the last column (row) to the first is no larger than the
// typical step between neighbours inside the image.
TEST(DetailPatterns, TileSeamlessly) {
  for (uint32_t s = 0; s < vegetation::kDetailSurfaceCount; ++s) {
    const auto p = generateDetailPattern(static_cast<DetailSurface>(s), kSize);
    for (bool horizontal : {true, false}) {
      double inner = 0.0;
      for (uint32_t x = 0; x + 1 < kSize; ++x) inner += stepAcross(p, kSize, x, horizontal);
      inner /= (kSize - 1);
      EXPECT_LT(stepAcross(p, kSize, kSize - 1, horizontal), 1.6 * inner + 1.0)
          << "surface " << s << (horizontal ? " left/right" : " top/bottom") << " seam";
    }
  }
}

TEST(DetailPatterns, MipChainHalvesDownToOneTexelOfTheMean) {
  EXPECT_EQ(mipLevelCount(256), 9u);
  EXPECT_EQ(mipLevelCount(1), 1u);
  const auto level0 = generateDetailPattern(DetailSurface::Gravel, kSize);
  const auto chain = withMipChain(level0, kSize);
  size_t expected = 0;
  for (uint32_t s = kSize; s >= 1; s /= 2) expected += size_t{s} * s * 4;
  ASSERT_EQ(chain.size(), expected);
  EXPECT_TRUE(std::equal(level0.begin(), level0.end(), chain.begin()));
  const uint8_t* last = &chain[chain.size() - 4];
  for (size_t c = 0; c < 3; ++c) EXPECT_NEAR(last[c] / 255.0, channelMean(level0, c), 0.01);
  EXPECT_EQ(last[3], 255);
  // The texture data holds every surface's full chain, kDetailTextureSize on a side.
  size_t perLayer = 0;
  for (uint32_t s = kDetailTextureSize; s >= 1; s /= 2) perLayer += size_t{s} * s * 4;
  EXPECT_EQ(detailTextureData().size(), perLayer * vegetation::kDetailSurfaceCount);
}

TEST(TerrainDetailBlock, PacksTheDefaultTableForTheShader) {
  const auto types = vegetation::defaultTerrainTypes();
  const TerrainDetailUniforms u = packTerrainDetail(types);
  EXPECT_EQ(u.params.x, static_cast<float>(types.size()));
  EXPECT_EQ(u.params.y, 150.0f);
  EXPECT_EQ(u.params.z, 1500.0f);
  EXPECT_EQ(u.tiling.x, static_cast<float>(kDetailPeriodM));
  // Whole repeats per period, so the pattern is continuous when the camera's modulo wraps.
  EXPECT_EQ(u.tiling.y, std::floor(u.tiling.y));
  EXPECT_EQ(u.tiling.z, std::floor(u.tiling.z));
  for (size_t i = 0; i < types.size(); ++i) {
    EXPECT_EQ(glm::vec3(u.reference[i]), types[i].score.reference);
    EXPECT_EQ(u.reference[i].w, types[i].score.p);
    EXPECT_EQ(glm::vec3(u.weights[i]), types[i].score.weights);
    EXPECT_EQ(u.weights[i].w, static_cast<float>(types[i].surface));
  }
  for (size_t i = types.size(); i < vegetation::kMaxTerrainTypes; ++i) EXPECT_EQ(u.reference[i], glm::vec4(0.0f));
}

}  // namespace
}  // namespace vegstream::render
