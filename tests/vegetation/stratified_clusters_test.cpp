// vegetation/stratified_clusters.h: the exact cluster levels of eq. 19–22, the per-level stratum
// bijection and the reflected mapping of eq. 23–25.

#include <cmath>
#include <set>
#include <vector>

#include <glm/common.hpp>
#include <gtest/gtest.h>

#include "vegetation/stratified_clusters.h"

namespace vegstream::vegetation {
namespace {

TEST(StratifiedClusters, LevelIsTheSmallestPyramidalNumberReachingI) {
  uint32_t n = 1;
  for (uint32_t i = 1; i <= pyramidalNumber(200); ++i) {
    if (pyramidalNumber(n) < i) ++n;
    ASSERT_EQ(clusterLevel(i), n) << "cluster " << i;
  }
  EXPECT_EQ(clusterLevel(1), 1u);
  EXPECT_EQ(clusterLevel(2), 2u);
  EXPECT_EQ(clusterLevel(5), 2u);
  EXPECT_EQ(clusterLevel(6), 3u);
  EXPECT_EQ(clusterLevel(14), 3u);
  EXPECT_EQ(clusterLevel(15), 4u);
}

TEST(StratifiedClusters, Eq22IsExactUpToLevel11AndThenLags) {
  for (uint32_t i = 1; i <= pyramidalNumber(11); ++i) ASSERT_EQ(approximateClusterLevel(i), clusterLevel(i)) << i;
  // The first cluster of level 13 (i = P_12 + 1): eq. 22 still says 12.
  const uint32_t i = pyramidalNumber(12) + 1;
  EXPECT_EQ(clusterLevel(i), 13u);
  EXPECT_EQ(approximateClusterLevel(i), 12u);
}

TEST(StratifiedClusters, EveryCompleteLevelPutsOneClusterInEachStratum) {
  for (uint32_t offset : {0u, 7u, 123456789u, 0xffffffffu}) {
    for (uint32_t n = 1; n <= 40; ++n) {
      std::set<std::pair<uint32_t, uint32_t>> seen;
      for (uint32_t c = pyramidalNumber(n - 1); c < pyramidalNumber(n); ++c) {
        const Stratum s = clusterStratum(c, offset);
        ASSERT_EQ(s.level, n);
        ASSERT_LT(s.x, n);
        ASSERT_LT(s.y, n);
        seen.insert({s.x, s.y});
      }
      EXPECT_EQ(seen.size(), size_t{n} * n) << "level " << n << " offset " << offset;
    }
  }
}

TEST(StratifiedClusters, FirstClustersOfALevelAreSpreadApart) {
  // The first two clusters of level 8 are never neighbours: the stride is ≈ 0.618 n².
  for (uint32_t offset = 0; offset < 64; ++offset) {
    const Stratum a = clusterStratum(pyramidalNumber(7), offset), b = clusterStratum(pyramidalNumber(7) + 1, offset);
    const int dx = std::abs(int(a.x) - int(b.x)), dy = std::abs(int(a.y) - int(b.y));
    EXPECT_GE(std::max(dx, dy), 2) << offset;
  }
}

TEST(StratifiedClusters, ReflectionMapsTheSquareOntoTheTriangle) {
  for (float u = 0.0f; u < 1.0f; u += 0.0625f)
    for (float v = 0.0f; v < 1.0f; v += 0.0625f) {
      const glm::vec2 r = reflectIntoTriangle({u, v});
      EXPECT_GE(r.x, 0.0f);
      EXPECT_GE(r.y, 0.0f);
      EXPECT_LE(r.x + r.y, 1.0f);
      if (u + v < 1.0f) {
        EXPECT_EQ(r, glm::vec2(u, v));
      }
    }
  const glm::dvec3 p = pointOnTriangle({0, 0, 0}, {2, 0, 0}, {0, 4, 1}, {0.25f, 0.5f});
  EXPECT_DOUBLE_EQ(p.x, 0.5);
  EXPECT_DOUBLE_EQ(p.y, 2.0);
  EXPECT_DOUBLE_EQ(p.z, 0.5);
}

TEST(StratifiedClusters, AStratumBecomesACompactPieceOfTheTriangle) {
  // Level 6, every stratum: the reflected images of its corners span at most one stratum's
  // width in each coordinate (a parallelogram, not a strip across the triangle).
  const uint32_t n = 6;
  for (uint32_t x = 0; x < n; ++x)
    for (uint32_t y = 0; y < n; ++y) {
      glm::vec2 lo(2.0f), hi(-1.0f);
      for (float fx : {0.001f, 0.999f})
        for (float fy : {0.001f, 0.999f}) {
          const glm::vec2 r = reflectIntoTriangle(pointInStratum({n, x, y}, {fx, fy}));
          lo = glm::min(lo, r);
          hi = glm::max(hi, r);
        }
      EXPECT_LE(hi.x - lo.x, 1.0f / n + 1e-6f);
      EXPECT_LE(hi.y - lo.y, 1.0f / n + 1e-6f);
    }
}

}  // namespace
}  // namespace vegstream::vegetation
