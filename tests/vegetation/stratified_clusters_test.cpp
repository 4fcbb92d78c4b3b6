// vegetation/stratified_clusters.h: the exact cluster levels of eq. 19–22, the per-level stratum
// bijection and the reflected mapping of eq. 23–25.

#include <cmath>
#include <set>
#include <vector>

#include <glm/common.hpp>
#include <gtest/gtest.h>

#include "vegetation/plant_seeding.h"
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

TEST(StratifiedClusters, EachStratumIsItsOwnCellOfTheTriangle) {
  // Levels 1 … 9, every stratum: samples anywhere in the unit square land inside the triangle,
  // inside one cell of the level's n² (stratumAt gives back the stratum), at most 1/n across.
  for (uint32_t n = 1; n <= 9; ++n)
    for (uint32_t x = 0; x < n; ++x)
      for (uint32_t y = 0; y < n; ++y) {
        glm::vec2 lo(2.0f), hi(-1.0f);
        for (float fx : {0.02f, 0.3f, 0.6f, 0.97f})
          for (float fy : {0.02f, 0.3f, 0.6f, 0.97f}) {  // (no pair on a cell's edge)
            const glm::vec2 r = pointInStratum({n, x, y}, {fx, fy});
            EXPECT_GE(r.x, 0.0f);
            EXPECT_GE(r.y, 0.0f);
            EXPECT_LE(r.x + r.y, 1.0f + 1e-6f);
            const Stratum back = stratumAt(r, n);
            EXPECT_EQ(back.x, x) << n << " " << x << " " << y << " at " << fx << ", " << fy;
            EXPECT_EQ(back.y, y) << n << " " << x << " " << y << " at " << fx << ", " << fy;
            lo = glm::min(lo, r);
            hi = glm::max(hi, r);
          }
        EXPECT_LE(hi.x - lo.x, 1.0f / float(n) + 1e-6f);
        EXPECT_LE(hi.y - lo.y, 1.0f / float(n) + 1e-6f);
      }
}

TEST(StratifiedClusters, EveryCellOfACompleteLevelHoldsExactlyOneCluster) {
  // Issue 18's fold: reflecting square strata mapped (x, y) and (n − 1 − y, n − 1 − x) onto one
  // piece of the triangle. Now the centres of a complete level's clusters, on many triangles,
  // fall one into each of the level's n² cells.
  for (uint64_t key : {1ull, 77ull, 0x9e3779b97f4a7c15ull, 123456789ull})
    for (uint32_t n = 2; n <= 8; ++n) {
      std::vector<int> hits(size_t(n) * n, 0);
      for (uint32_t c = pyramidalNumber(n - 1); c < pyramidalNumber(n); ++c) {
        const Stratum s = stratumAt(clusterCentre(key, c), n);
        ++hits[size_t(s.y) * n + s.x];
      }
      for (size_t cell = 0; cell < hits.size(); ++cell) EXPECT_EQ(hits[cell], 1) << "level " << n << " cell " << cell;
    }
}

}  // namespace
}  // namespace vegstream::vegetation
