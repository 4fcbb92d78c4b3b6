#pragma once
// Bins of seed triangles by cluster count, core seed ../shared/seeds/001_3eca9f2c7752e4fb.txt
// §3.2, eq. 15: n_b bins (32) with geometric centres
//
//     c_i = n_min (n_max / n_min)^(i / (n_b − 1)),   i = 0 … n_b − 1,
//
// n_min, n_max the smallest and largest count of this frame's triangles (re-centred every frame
// — the counts are known before the bins are built, so this frame's, not the last one's).
//
// The paper draws each bin instanced with the bin's centre as the instance count, which rounds
// every triangle's plant count to its bin. The classify pass is the compute equivalent without
// that rounding: a triangle goes to the smallest bin whose capacity ⌈c_i⌉ holds its count, one
// dispatch per bin covers capacity × triangles threads, and a thread beyond its triangle's own
// count does nothing — so plant counts stay exact (and continuous, for the fade) and the only
// cost of binning is the idle threads, bounded by the ratio between neighbouring centres.

#include <cstdint>
#include <span>
#include <vector>

namespace vegstream::vegetation {

inline constexpr uint32_t kDefaultBins = 32;

struct PlantBin {
  float centre = 0.0f;    // c_i
  uint32_t capacity = 0;  // ⌈c_i⌉: clusters per triangle this bin's dispatch covers
  uint32_t first = 0;     // into BinnedTriangles::order
  uint32_t count = 0;     // triangles in the bin
};

struct BinnedTriangles {
  std::vector<PlantBin> bins;   // n_b of them, increasing centres (empty: no triangle)
  std::vector<uint32_t> order;  // triangle indices grouped by bin, each bin in input order
  uint32_t minCount = 0, maxCount = 0;
  uint64_t clusters = 0;  // Σ counts
  uint64_t slots = 0;     // Σ capacity × count: threads the dispatches cover
};

// Bins the triangles with counts[i] clusters (0: left out). binCount ≥ 1.
BinnedTriangles binTriangles(std::span<const uint32_t> counts, uint32_t binCount = kDefaultBins);

}  // namespace vegstream::vegetation
