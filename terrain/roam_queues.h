#pragma once
// RoamQueues (internal to the tessellator, roam_tessellator.h update(), steps 2 and 3): the
// split and merge queues of one update (Duchaineau et al. 1997 §6: queues under budgets). It
// owns no state between updates: it changes the mesh from the candidates the priority traversal
// found (roam_priorities.h) and decides when a held-back candidate is looked at again (its
// deadline).
//
// Contract:
//   - split(): the largest priorities above the bound first; each split's new leaves (forced
//     splits' included) are computed at once and queued when above the bound; until the bound is
//     met, the triangle budget is reached (forced splits go on) or the work budget is spent
//     (RoamOptions::maxOpsPerFrame operations, and maxQueueMs when set). achievedErrorPx: what
//     the budgets left unsplit.
//   - merge(): each diamond once, lowest priority first, below mergeFraction × the bound or, while
//     the mesh is over budget, any; for the error the split vertex first sinks to its base over
//     fadeS (the merge waits for it), for the budget (or unseen) it merges at once.
// Counts splits, merges, mergesStarted, leavesCreated, depthLimitedLeaves and the budget flags
// into the figures.

#include <cstdint>
#include <vector>

#include "core/stopwatch.h"
#include "terrain/eye_space.h"
#include "terrain/roam_mesh.h"
#include "terrain/roam_priorities.h"
#include "terrain/roam_tessellator.h"

namespace vegstream::terrain {

class RoamQueues {
 public:
  // Every reference outlives this; `options` is read live (RoamTessellator::setMaxErrorPx).
  RoamQueues(RoamMesh& mesh, const RoamOptions& options, RoamPriorities& priorities, RoamFigures& figures);

  // `candidates`: the split candidates (a heap afterwards); `ops`: the update's operations so far.
  void split(const EyeView& view, const Frustum& frustum, const PieceSet& pieces, std::vector<Candidate>& candidates,
             uint64_t& ops, const Stopwatch& watch);
  // `diamonds`: the merge candidates (sorted afterwards); `timeS`: the update's (morphs).
  void merge(std::vector<Candidate>& diamonds, double timeS, uint64_t& ops, const Stopwatch& watch);

 private:
  bool outOfWork(uint64_t ops, const Stopwatch& watch);
  // What the budgets left unsplit in `heap` is what the mesh misses the bound by.
  void recordUnsplit(const EyeView& view, const std::vector<Candidate>& heap);
  // The diamonds to merge, each pair once, lowest first; the others are held (deadlines).
  std::vector<Candidate> mergeQueue(std::vector<Candidate>& diamonds, double threshold, bool overBudget);
  void lowerDeadline(uint32_t t, double deadline);  // and its ancestors' subtree deadlines

  RoamMesh& mesh_;
  const RoamOptions& options_;
  RoamPriorities& priorities_;
  RoamFigures& figures_;
};

}  // namespace vegstream::terrain
