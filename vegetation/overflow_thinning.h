#pragma once
// Overflow thinning (issue 18: "when a buffer overflows, drop by a view-independent priority,
// never by atomic order", and no plant may pop). Not from the seeds: the core seed's
// (../shared/seeds/001_3eca9f2c7752e4fb.txt §3.5) species buffers are fixed-size and simply
// drop what no longer fits, in whatever order the GPU's threads append.
//
// Each group (a cluster, or one seed of cluster 0) has a priority u in [0, 1) from a Philox draw
// of its triangle's key and its cluster index, so the same groups go first from any camera; the
// seeds of cluster 0 step through it by the golden ratio (a Weyl sequence in 32-bit integers,
// exact on CPU and GPU), so a triangle's seeds are spread over the priorities instead of going
// together, which would make the count thinned away jumpy. A
// species under pressure p in [0, 1) keeps a group at the size factor
//
//     thinningFade(p, u) = clamp(((1 + b)(1 − p) − u) / b, 0, 1),     b = kThinningBand
//
// p = 0 keeps every group whole; as p grows the lowest-priority groups shrink away over a band
// b of priorities, so a group never vanishes at more than a small fraction of its size.
//
// The pressure comes from the groups the species wanted in an earlier frame, C (before
// thinning), and its buffer's capacity K:
//
//     p = 1 − min(1, T / C),   T = kThinningStart · K
//
// Groups appended: C while (1 + b)(1 − p) ≥ 1, else (1 + b)(1 − p) C = (1 + b) T; with
// kThinningStart = 0.75 and b = 0.25 that is at most 0.94 K, so a buffer fills only when the
// wanted groups jump between frames (then the frame's figures say it overflowed). p is
// continuous in C, so a slow flight changes each group's size slowly. The GLSL twin is in
// shaders/classify.comp (thinningFade) with groupPriority in shaders/common/seeding.glsl.

#include <cstdint>

namespace vegstream::vegetation {

inline constexpr float kThinningBand = 0.25f;
inline constexpr float kThinningStart = 0.75f;

// u01(y + seed · 0x9E3779B9) with y the second word of Philox draw (cluster,
// philox_slot::kSpecies) of the triangle's key (the first word is the cluster's species z;
// cluster 0 does not use this draw otherwise). `seed`: the group's first seed (0 for c ≥ 1).
float groupPriority(uint64_t key, uint32_t cluster, uint32_t seed);

// The size factor above; pressure 0 gives 1 for every priority in [0, 1).
float thinningFade(float pressure, float priority);

// The pressure for a species that wanted `wantedGroups` with buffer capacity `capacity` (> 0).
float thinningPressure(uint64_t wantedGroups, uint32_t capacity);

}  // namespace vegstream::vegetation
