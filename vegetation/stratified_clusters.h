#pragma once
// Hierarchical stratified sampling of clusters on a seed triangle, core seed
// ../shared/seeds/001_3eca9f2c7752e4fb.txt §3.4 (eq. 19–25), §2.2 (eq. 3).
//
// Clusters are numbered i = 1, 2, 3, … (the paper's numbering; code passes the 0-based
// c = i − 1). The first cluster is sampled from the whole triangle, the next 4 from a 2 × 2
// partition of the unit square, the next 9 from 3 × 3 and so on: after level n there are
// P_n = Σ k² = (2n³ + 3n² + n) / 6 clusters (eq. 19), so cluster i belongs to the smallest
// level n with P_n ≥ i — the ceiling of the real root of P_n − i = 0 (eq. 20–21). The seed
// approximates that root by r = ∛(3i) − ½ (eq. 22); that estimate is exact up to level 11 and
// then lags (at i = P_n + 1 it stays at n for n ≥ 12), so we start from it and correct it
// with integer comparisons: the level is exact and identical in C++ and GLSL.
//
// Within a level the k-th cluster (k = i − P_{n−1} − 1, 0 … n² − 1) takes stratum
// (a·k + b) mod n²: a fixed multiplier near 0.618 n² coprime with n (so the map is a
// bijection and successive clusters land far apart — a triangle whose last level is only
// partly filled still has its clusters spread over the whole triangle), b a per-triangle,
// per-level random offset. The paper picks "a randomly chosen stratum"; a bijection also
// guarantees every stratum of a complete level exactly one cluster.
//
// The strata are the triangle's own: dividing each side into n parts cuts the unit triangle
// (r′1, r′2 ≥ 0, r′1 + r′2 ≤ 1) into n² congruent triangles, n(n + 1)/2 upright and n(n − 1)/2
// inverted. Stratum (x, y) of the n × n square is upright cell (x, y) when x + y < n, else the
// inverted cell (n − 1 − y, n − 1 − x) — a bijection, so every stratum of a complete level holds
// exactly one cluster and the clusters of a level cover the triangle evenly. A point of a cell
// comes from a unit-square sample reflected into the unit triangle (eq. 23–24) and scaled into
// the cell, then the affine map p = v0 + r′1 (v1 − v0) + r′2 (v2 − v0) (eq. 25) places it; v0 is
// the apex (the right angle), v1 left, v2 right. (Reflecting the square's strata themselves, as
// eq. 23–24 do for the whole square, folds stratum (x, y) onto (n − 1 − y, n − 1 − x): two
// clusters of a level could share a piece of the triangle while another stayed empty.)
//
// shaders/common/seeding.glsl is the GLSL twin, integer for integer.

#include <algorithm>
#include <cassert>
#include <cstdint>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace vegstream::vegetation {

// P_n of eq. 19.
constexpr uint32_t pyramidalNumber(uint32_t n) { return n * (n + 1) * (2 * n + 1) / 6; }

// The deepest level supported: P_1000 ≈ 3.3e8 clusters per triangle, far above any n_max.
inline constexpr uint32_t kMaxStratificationLevel = 1000;

// ⌈∛(3i) − ½⌉, at least 1 (eq. 22), for the 1-based cluster number i ≥ 1.
uint32_t approximateClusterLevel(uint32_t i);
// The level of cluster number i ≥ 1: the smallest n with P_n ≥ i (eq. 20).
uint32_t clusterLevel(uint32_t i);

// The stride of level n's stratum permutation: the integer nearest 0.618 n² coprime with n
// (1 for n = 1).
uint32_t strataStride(uint32_t n);

struct Stratum {
  uint32_t level = 1;     // the partition is level × level
  uint32_t x = 0, y = 0;  // the stratum's column and row, each in [0, level)
};

// The stratum of 0-based cluster c given its level's random offset (any 32-bit value).
Stratum clusterStratum(uint32_t c, uint32_t levelOffset);

// Eq. 23–24: (u, v) in [0, 1)² → (r′1, r′2) with r′1, r′2 ≥ 0, r′1 + r′2 ≤ 1.
inline glm::vec2 reflectIntoTriangle(glm::vec2 r) {
  if (r.x + r.y >= 1.0f) return {1.0f - r.y, 1.0f - r.x};
  return r;
}

// The point of stratum `s` that the unit-square sample `f` ∈ [0, 1)² maps to, on the unit
// triangle (r′1, r′2): uniform samples give uniform points of the stratum's cell.
inline glm::vec2 pointInStratum(const Stratum& s, glm::vec2 f) {
  const float n = static_cast<float>(s.level);
  const glm::vec2 t = reflectIntoTriangle(f);
  if (s.x + s.y < s.level)  // upright cell (x, y)
    return {(static_cast<float>(s.x) + t.x) / n, (static_cast<float>(s.y) + t.y) / n};
  // Inverted cell (n − 1 − y, n − 1 − x): its right angle at ((n − y) / n, (n − x) / n).
  return {(static_cast<float>(s.level - s.y) - t.x) / n, (static_cast<float>(s.level - s.x) - t.y) / n};
}

// The cell of level n that holds point `r` of the unit triangle, as the stratum (x, y) that
// pointInStratum maps onto it (for tests and figures).
inline Stratum stratumAt(glm::vec2 r, uint32_t n) {
  const float fx = r.x * static_cast<float>(n), fy = r.y * static_cast<float>(n);
  const auto i = static_cast<uint32_t>(std::min(std::max(fx, 0.0f), static_cast<float>(n - 1)));
  const auto j = static_cast<uint32_t>(std::min(std::max(fy, 0.0f), static_cast<float>(n - 1)));
  if ((fx - static_cast<float>(i)) + (fy - static_cast<float>(j)) < 1.0f || i + j + 1 >= n) return {n, i, j};
  return {n, n - 1 - j, n - 1 - i};  // inverted cell (i, j)
}

// Eq. 25, in double (the CPU reference; the GPU does it in float relative to the camera).
inline glm::dvec3 pointOnTriangle(const glm::dvec3& v0, const glm::dvec3& v1, const glm::dvec3& v2, glm::vec2 rPrime) {
  return v0 + static_cast<double>(rPrime.x) * (v1 - v0) + static_cast<double>(rPrime.y) * (v2 - v0);
}

}  // namespace vegstream::vegetation
