// ROAM update, step 1: the priority traversal (roam_tessellator.h update(), step 1). Seed
// 001_3eca9f2c7752e4fb.txt §3.1 (the projected wedgie error, hierarchical culling); Duchaineau
// et al. 1997 §6 (deferred priority recomputation).
//
// In parallel (RoamOptions::tasks): the frame thread walks the nodes of more than kTaskLeaves
// leaves and hands each subtree below them to a task. A subtree's traversal writes only its own
// nodes, so the tasks are independent but for three things, kept apart and put back together
// on the frame thread as one traversal would have them: the split and merge candidates, in
// traversal order (the queues' order, hence the mesh, depends on it); the merge morphs to
// cancel (they mark leaves on both sides of a diamond, possibly in another subtree: nothing the
// traversal reads); and the subtree deadlines of the nodes above the tasks (post-order).

#include <algorithm>
#include <cassert>

#include "core/parallel_for.h"
#include "terrain/roam_error.h"
#include "terrain/roam_tessellator.h"
#include "terrain/roam_walk.h"

namespace vegstream::terrain {

void RoamTessellator::PriorityFigures::add(const PriorityFigures& o) {
  visited += o.visited;
  computed += o.computed;
  achievedErrorPx = std::max(achievedErrorPx, o.achievedErrorPx);
}

void RoamTessellator::computePriorities(Walk& w) {
  std::vector<uint32_t> cancels;
  w.cancels = &cancels;
  w.tasks = options_.tasks ? &priorityTasks_ : nullptr;
  w.taskCount = 0;
  w.waiting.clear();
  for (uint32_t r : mesh_.roots()) {
    glm::dvec3 eye[3];
    eyeOf(*w.view, r, eye);
    descendPriorities(w, r, eye, Cull::Partial, kEveryPlane, InPiece::None);
  }
  if (w.taskCount > 0) {
    const auto run = [&](size_t k) -> Status {
      PriorityTask& task = priorityTasks_[k];
      Walk tw;
      tw.view = w.view;
      tw.frustum = w.frustum;
      tw.pieces = w.pieces;
      tw.bound = w.bound;
      tw.mergeBelow = w.mergeBelow;
      tw.overBudget = w.overBudget;
      tw.splits = &task.splits;
      tw.diamonds = &task.diamonds;
      tw.cancels = &task.cancels;
      visitPriorities(tw, task.node, task.cull == Cull::Outside ? nullptr : task.eye, task.cull, task.planes, task.ps);
      task.counts = tw.counts;
      return {};
    };
    const Status done = parallelFor(w.taskCount, 0, options_.tasks, run);
    assert(done.ok());
    (void)done;
    // The candidates in traversal order. The top pushes none: its nodes hold more than
    // kTaskLeaves ≥ 2 leaves, so none is a leaf or a diamond.
    assert(w.splits->empty() && w.diamonds->empty());
    for (size_t k = 0; k < w.taskCount; ++k) {
      const PriorityTask& task = priorityTasks_[k];
      w.splits->insert(w.splits->end(), task.splits.begin(), task.splits.end());
      w.diamonds->insert(w.diamonds->end(), task.diamonds.begin(), task.diamonds.end());
      cancels.insert(cancels.end(), task.cancels.begin(), task.cancels.end());
      w.counts.add(task.counts);
    }
  }
  // The nodes above the tasks, children first.
  for (uint32_t t : w.waiting) {
    RoamNode& n = mesh_.node(t);
    n.subtreeDeadline =
        std::min({n.deadline, mesh_.node(n.child).subtreeDeadline, mesh_.node(n.child + 1).subtreeDeadline});
  }
  // Cancelling is idempotent and writes nothing the traversal reads: done after it, in any
  // order, it gives what cancelling on the way gave.
  for (uint32_t t : cancels) mesh_.cancelMergeMorph(t);
  figures_.priorityTasks = w.taskCount;
  figures_.nodesVisited = w.counts.visited;
  figures_.prioritiesComputed = w.counts.computed;
  figures_.achievedErrorPx = w.counts.achievedErrorPx;
}

void RoamTessellator::descendPriorities(Walk& w, uint32_t t, const glm::dvec3* eye, Cull cull, PlaneMask planes,
                                        InPiece ps) {
  if (!w.tasks || mesh_.node(t).leafCount > kTaskLeaves) {
    visitPriorities(w, t, eye, cull, planes, ps);
    return;
  }
  if (w.taskCount == w.tasks->size()) w.tasks->emplace_back();
  PriorityTask& task = (*w.tasks)[w.taskCount++];
  task.node = t;
  if (cull != Cull::Outside) std::copy(eye, eye + 3, task.eye);
  task.cull = cull;
  task.planes = planes;
  task.ps = ps;
  task.splits.clear();
  task.diamonds.clear();
  task.cancels.clear();
  task.counts = {};
}

void RoamTessellator::visitPriorities(Walk& w, uint32_t t, const glm::dvec3* eye, Cull cull, PlaneMask planes,
                                      InPiece ps) {
  RoamNode& n = mesh_.node(t);
  mesh_.prefetchChildrenForPriorities(t);
  const int level = n.path.level;
  if (cull == Cull::Partial) {
    const double e = n.cullThickness();
    cull = cullWedgie(*w.frustum, eye[0], eye[1], eye[2], e, e + options_.canopyM, planes);
  }
  if (level == 0 || (ps == InPiece::Above && level % 2 == 0))
    ps = pieceState(*w.pieces, mesh_.grid().square(mesh_.corners(t), level), ps, level);
  const bool seenSame = n.seenCull == static_cast<uint8_t>(cull) && n.seenPiece == static_cast<uint8_t>(ps);
  // Nothing below is due and it is wholly in (or out of) the view and the pieces as before:
  // every priority below is still on the same side of its bounds (Inside and Outside, In and
  // None hold for the whole subtree).
  if (!evaluateAll_ && seenSame && cull != Cull::Partial && ps != InPiece::Above && n.subtreeDeadline > odometerM_)
    return;
  const bool due = evaluateAll_ || !seenSame || !(n.deadline > odometerM_);
  ++w.counts.visited;
  if (n.isLeaf()) {
    if (due) evaluateLeaf(*w.view, t, eye, cull, ps, w.counts);
    if (n.priority > w.bound) w.splits->push_back({n.priority, t, n.path});
    n.subtreeDeadline = n.deadline;
    return;
  }
  const uint32_t c = n.child;
  if (mesh_.node(c).isLeaf() && mesh_.node(c + 1).isLeaf()) {
    if (due) evaluateDiamond(w, t, eye, cull, ps);
    // A diamond merges below the threshold (its priority is the larger half's), or for the budget.
    if (n.priority < w.mergeBelow || w.overBudget) w.diamonds->push_back({n.priority, t, n.path});
  } else if (due) {
    n.priority = kForcedPriority;  // not a diamond half: never merged as one
    n.deadline = kNever;
    n.seenCull = static_cast<uint8_t>(cull);
    n.seenPiece = static_cast<uint8_t>(ps);
    w.cancels->push_back(t);
  }
  // Children the deferral skips on entry (the test at the top, for a cull and piece state
  // they inherit unchanged) need no eye coordinates: do not transform the split vertex for them.
  auto skipped = [&](uint32_t child) {
    const RoamNode& x = mesh_.node(child);
    return !evaluateAll_ && cull != Cull::Partial && (ps == InPiece::In || ps == InPiece::None) &&
           x.seenCull == static_cast<uint8_t>(cull) && x.seenPiece == static_cast<uint8_t>(ps) &&
           x.subtreeDeadline > odometerM_;
  };
  const bool top = w.tasks != nullptr;  // children may be tasks: the subtree deadline waits
  const bool skip0 = skipped(c), skip1 = skipped(c + 1);
  if (!skip0 || !skip1) {
    glm::dvec3 e0[3], e1[3];
    if (cull != Cull::Outside) {
      const glm::dvec3 m = eyeOfVertex(*w.view, n.mid);
      e0[0] = m;
      e0[1] = eye[0];
      e0[2] = eye[1];
      e1[0] = m;
      e1[1] = eye[2];
      e1[2] = eye[0];
    }
    // A skipped child would return at once (the test at the top) with nothing written: it is
    // not entered, nor made a task.
    if (top) {
      if (!skip0) descendPriorities(w, c, e0, cull, planes, ps);
      if (!skip1) descendPriorities(w, c + 1, e1, cull, planes, ps);
    } else {
      if (!skip0) visitPriorities(w, c, e0, cull, planes, ps);
      if (!skip1) visitPriorities(w, c + 1, e1, cull, planes, ps);
    }
  }
  if (top) {
    w.waiting.push_back(t);
    return;
  }
  RoamNode& after = mesh_.node(t);
  after.subtreeDeadline = std::min({after.deadline, mesh_.node(c).subtreeDeadline, mesh_.node(c + 1).subtreeDeadline});
}

void RoamTessellator::evaluateLeaf(const EyeView& view, uint32_t t, const glm::dvec3* eye, Cull cull, InPiece ps,
                                   PriorityFigures& counts) {
  RoamNode& n = mesh_.node(t);
  n.seenCull = static_cast<uint8_t>(cull);
  n.seenPiece = static_cast<uint8_t>(ps);
  ErrorGeometry g;
  n.priority = priority(view, t, eye, cull, ps, &g);
  ++counts.computed;
  // Outside, or no data: 0 until the cull or the mesh changes (both checked without a deadline).
  if (n.priority == 0.0f) {
    n.deadline = kNever;
    return;
  }
  if (n.priority > options_.maxErrorPx) {  // to be split: every update looks at it again
    n.deadline = kNow;
    return;
  }
  counts.achievedErrorPx = std::max(counts.achievedErrorPx, double(n.priority));
  double safe = g.safeDistance(options_.maxErrorPx, true);
  // The seed-level constraint starts where the sphere comes within the horizon.
  if (seeds_.refineToSeedLevel && n.path.level < seedLevel_)
    safe = std::min(safe, std::max(0.0, g.dc - g.r - seeds_.horizonM));
  n.deadline = odometerM_ + safe;
}

void RoamTessellator::evaluateDiamond(Walk& w, uint32_t t, const glm::dvec3* eye, Cull cull, InPiece ps) {
  RoamNode& n = mesh_.node(t);
  n.seenCull = static_cast<uint8_t>(cull);
  n.seenPiece = static_cast<uint8_t>(ps);
  ErrorGeometry g;
  n.priority = priority(*w.view, t, eye, cull, ps, &g);
  ++w.counts.computed;
  if (n.priority < w.mergeBelow) {
    // A merge candidate: the merge phase decides when to look again (at once while it waits for
    // its morph or the work budget; while its partner holds it, until either may change).
    n.deadline = n.priority == 0.0f ? kNever : odometerM_ + g.safeDistance(w.mergeBelow, true);
    return;
  }
  w.cancels->push_back(t);     // it sank towards a merge that is no longer wanted
  if (ps == InPiece::Above) {  // forced by the pieces: their changes are seen without a deadline
    n.deadline = kNever;
    return;
  }
  if (n.priority >= kForcedPriority) {  // forced by the seed level until the sphere leaves the horizon
    n.deadline = odometerM_ + std::max(0.0, seeds_.horizonM - g.sphereDistance());
    return;
  }
  n.deadline = odometerM_ + g.safeDistance(w.mergeBelow, false);
}

}  // namespace vegstream::terrain
