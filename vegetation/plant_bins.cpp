// Geometric bins, core seed 001_3eca9f2c7752e4fb.txt §3.2 eq. 15.
#include "vegetation/plant_bins.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace vegstream::vegetation {

BinnedTriangles binTriangles(std::span<const uint32_t> counts, uint32_t binCount) {
  assert(binCount >= 1);
  BinnedTriangles out;
  uint32_t lo = UINT32_MAX, hi = 0;
  for (uint32_t c : counts)
    if (c > 0) lo = std::min(lo, c), hi = std::max(hi, c);
  if (hi == 0) return out;
  out.minCount = lo;
  out.maxCount = hi;
  out.bins.resize(binCount);
  const double ratio = static_cast<double>(hi) / static_cast<double>(lo);
  for (uint32_t i = 0; i < binCount; ++i) {
    const double t = binCount == 1 ? 1.0 : static_cast<double>(i) / static_cast<double>(binCount - 1);
    const double c = static_cast<double>(lo) * std::pow(ratio, t);  // eq. 15
    out.bins[i].centre = static_cast<float>(c);
    // The last bin holds the maximum exactly (pow may land a hair below it).
    out.bins[i].capacity = i + 1 == binCount ? hi : std::max(lo, static_cast<uint32_t>(std::ceil(c - 1e-9)));
  }
  // Bin of each triangle: the smallest capacity ≥ its count.
  std::vector<uint32_t> binOf(counts.size(), binCount);
  for (size_t t = 0; t < counts.size(); ++t) {
    if (counts[t] == 0) continue;
    const auto it = std::lower_bound(out.bins.begin(), out.bins.end(), counts[t],
                                     [](const PlantBin& b, uint32_t c) { return b.capacity < c; });
    assert(it != out.bins.end());
    binOf[t] = static_cast<uint32_t>(it - out.bins.begin());
    ++it->count;
    out.clusters += counts[t];
  }
  uint32_t first = 0;
  for (PlantBin& b : out.bins) {
    b.first = first;
    first += b.count;
    out.slots += uint64_t{b.capacity} * b.count;
  }
  out.order.resize(first);
  std::vector<uint32_t> fill(binCount, 0);
  for (size_t t = 0; t < counts.size(); ++t) {
    const uint32_t b = binOf[t];
    if (b == binCount) continue;
    out.order[out.bins[b].first + fill[b]++] = static_cast<uint32_t>(t);
  }
  return out;
}

}  // namespace vegstream::vegetation
