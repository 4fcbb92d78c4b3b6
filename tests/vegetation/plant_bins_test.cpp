// vegetation/plant_bins.h: eq. 15's geometric centres and exact, complete bin assignment.

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include <gtest/gtest.h>

#include "vegetation/plant_bins.h"

namespace vegstream::vegetation {
namespace {

TEST(PlantBins, CentresAreTheGeometricProgressionOfEq15) {
  const std::vector<uint32_t> counts = {3, 1, 0, 40, 12, 7, 1, 33, 2};
  const BinnedTriangles b = binTriangles(counts);
  ASSERT_EQ(b.bins.size(), kDefaultBins);
  EXPECT_EQ(b.minCount, 1u);
  EXPECT_EQ(b.maxCount, 40u);
  for (uint32_t i = 0; i < kDefaultBins; ++i)
    EXPECT_NEAR(b.bins[i].centre, std::pow(40.0, i / 31.0), 1e-4 * b.bins[i].centre) << i;
  EXPECT_EQ(b.bins.front().capacity, 1u);
  EXPECT_EQ(b.bins.back().capacity, 40u);
}

TEST(PlantBins, EveryTriangleLandsOnceInTheSmallestBinThatHoldsIt) {
  std::vector<uint32_t> counts;
  for (uint32_t i = 0; i < 5000; ++i) counts.push_back((i * 2654435761u >> 7) % 300);  // 0 … 299
  const BinnedTriangles b = binTriangles(counts);
  std::vector<uint32_t> seen(counts.size(), 0);
  uint64_t clusters = 0, slots = 0;
  for (size_t k = 0; k < b.bins.size(); ++k) {
    const PlantBin& bin = b.bins[k];
    for (uint32_t j = bin.first; j < bin.first + bin.count; ++j) {
      const uint32_t t = b.order[j];
      ++seen[t];
      EXPECT_LE(counts[t], bin.capacity);
      if (k > 0) {
        EXPECT_GT(counts[t], b.bins[k - 1].capacity);
      }
      clusters += counts[t];
    }
    slots += uint64_t{bin.capacity} * bin.count;
  }
  for (size_t t = 0; t < counts.size(); ++t) EXPECT_EQ(seen[t], counts[t] > 0 ? 1u : 0u) << t;
  EXPECT_EQ(clusters, b.clusters);
  EXPECT_EQ(slots, b.slots);
  EXPECT_EQ(clusters, std::accumulate(counts.begin(), counts.end(), uint64_t{0}));
  // Idle threads stay below the step between neighbouring centres: (299)^(1/31) ≈ 1.2, plus the
  // rounding of the small bins.
  EXPECT_LT(static_cast<double>(b.slots) / static_cast<double>(b.clusters), 1.3);
}

TEST(PlantBins, NothingToBinGivesNoBins) {
  EXPECT_TRUE(binTriangles(std::vector<uint32_t>{0, 0}).bins.empty());
  EXPECT_TRUE(binTriangles({}).order.empty());
  const BinnedTriangles one = binTriangles(std::vector<uint32_t>{5, 5});
  EXPECT_EQ(one.order.size(), 2u);
  for (const PlantBin& bin : one.bins) EXPECT_EQ(bin.capacity, 5u);
}

}  // namespace
}  // namespace vegstream::vegetation
