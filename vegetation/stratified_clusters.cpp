// Hierarchical stratified clusters, core seed 001_3eca9f2c7752e4fb.txt §3.4 eq. 19–25.
// Integer logic mirrored by shaders/common/seeding.glsl.
#include "vegetation/stratified_clusters.h"

#include <cmath>
#include <numeric>

namespace vegstream::vegetation {

uint32_t approximateClusterLevel(uint32_t i) {
  assert(i >= 1);
  const double r = std::cbrt(3.0 * static_cast<double>(i)) - 0.5;
  return std::max(1u, static_cast<uint32_t>(std::ceil(r)));
}

uint32_t clusterLevel(uint32_t i) {
  assert(i >= 1 && i <= pyramidalNumber(kMaxStratificationLevel));
  // Eq. 22's estimate, then exact by integer steps (at most a few either way).
  uint32_t n = std::min(approximateClusterLevel(i), kMaxStratificationLevel);
  while (pyramidalNumber(n) < i) ++n;
  while (n > 1 && pyramidalNumber(n - 1) >= i) --n;
  return n;
}

uint32_t strataStride(uint32_t n) {
  assert(n >= 1);
  if (n == 1) return 1;
  const uint32_t cells = n * n;
  // 0.618 n² in integers (n ≤ 1000: no overflow), then the next value coprime with n.
  uint32_t a = (cells * 618u + 500u) / 1000u;
  while (std::gcd(a, n) != 1u) ++a;
  return a % cells;
}

Stratum clusterStratum(uint32_t c, uint32_t levelOffset) {
  const uint32_t n = clusterLevel(c + 1);
  const uint32_t cells = n * n;
  const uint32_t k = c - pyramidalNumber(n - 1);  // index within the level
  assert(k < cells);
  // (a·k + b) mod n² in 64 bits: a, k < n² ≤ 10⁶.
  const uint64_t s = (uint64_t{strataStride(n)} * k + levelOffset % cells) % cells;
  return {n, static_cast<uint32_t>(s % n), static_cast<uint32_t>(s / n)};
}

}  // namespace vegstream::vegetation
