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
// A point (u, v) of the unit square goes onto the triangle by reflecting the half above the
// diagonal (eq. 23–24) and the affine map p = v0 + r′1 (v1 − v0) + r′2 (v2 − v0) (eq. 25). A
// square stratum then becomes a parallelogram (or, on the diagonal, a triangle folded onto
// itself), not the trapezoid of eq. 3, and uniform samples of the square are uniform on the
// triangle. v0 is the apex (the right angle), v1 left, v2 right.
//
// shaders/common/seeding.glsl is the GLSL twin, integer for integer.

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

// A point of stratum `s` at fractional position `f` ∈ [0, 1)² inside it, on the unit square.
inline glm::vec2 pointInStratum(const Stratum& s, glm::vec2 f) {
  const float n = static_cast<float>(s.level);
  return {(static_cast<float>(s.x) + f.x) / n, (static_cast<float>(s.y) + f.y) / n};
}

// Eq. 25, in double (the CPU reference; the GPU does it in float relative to the camera).
inline glm::dvec3 pointOnTriangle(const glm::dvec3& v0, const glm::dvec3& v1, const glm::dvec3& v2, glm::vec2 rPrime) {
  return v0 + static_cast<double>(rPrime.x) * (v1 - v0) + static_cast<double>(rPrime.y) * (v2 - v0);
}

}  // namespace vegstream::vegetation
