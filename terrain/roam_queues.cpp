// RoamQueues (roam_queues.h): ROAM update, steps 2 and 3, the split and merge queues under a
// triangle budget and a work budget. Seed 001_3eca9f2c7752e4fb.txt §3.1; Duchaineau et al. 1997
// §6 (split/merge queues, budgets).

#include "terrain/roam_queues.h"

#include <algorithm>

namespace vegstream::terrain {

RoamQueues::RoamQueues(RoamMesh& mesh, const RoamOptions& options, RoamPriorities& priorities, RoamFigures& figures)
    : mesh_(mesh), options_(options), priorities_(priorities), figures_(figures) {}

bool RoamQueues::outOfWork(uint64_t ops, const Stopwatch& watch) {
  if (ops >= options_.maxOpsPerFrame || (options_.maxQueueMs > 0.0 && watch.elapsedMs() > options_.maxQueueMs)) {
    figures_.workLimited = true;
    return true;
  }
  return false;
}

void RoamQueues::split(const EyeView& view, const Frustum& frustum, const PieceSet& pieces,
                       std::vector<Candidate>& heap, uint64_t& ops, const Stopwatch& watch) {
  auto less = [](const Candidate& a, const Candidate& b) { return a.priority < b.priority; };
  std::make_heap(heap.begin(), heap.end(), less);
  const double bound = options_.maxErrorPx;
  std::vector<uint32_t> created;
  while (!heap.empty() && heap.front().priority > bound) {
    if (outOfWork(ops, watch)) break;
    const bool forced = heap.front().priority >= kForcedPriority;
    if (!forced && mesh_.leafCount() + 2 > options_.maxTriangles) {
      figures_.budgetLimited = true;
      break;
    }
    std::pop_heap(heap.begin(), heap.end(), less);
    const Candidate c = heap.back();
    heap.pop_back();
    const RoamNode& n = mesh_.node(c.node);
    if (!n.isLeaf() || n.path != c.path) continue;  // split or removed since it was queued
    created.clear();
    if (!mesh_.split(c.node, &created)) {  // at the deepest level
      if (c.priority < kForcedPriority) {
        ++figures_.depthLimitedLeaves;
        figures_.achievedErrorPx = std::max(figures_.achievedErrorPx, double(c.priority));
      }
      continue;
    }
    ++ops;
    ++figures_.splits;
    figures_.leavesCreated += created.size();
    // The new leaves (the diamond's and the forced splits') may need more splits this frame.
    for (uint32_t leaf : created) {
      if (!mesh_.node(leaf).isLeaf()) continue;
      const float p = priorities_.evaluateNewLeaf(view, frustum, pieces, leaf, figures_);
      if (p > bound) {
        heap.push_back({p, leaf, mesh_.node(leaf).path});
        std::push_heap(heap.begin(), heap.end(), less);
      }
    }
  }
  recordUnsplit(view, heap);
}

void RoamQueues::recordUnsplit(const EyeView& view, const std::vector<Candidate>& heap) {
  for (const Candidate& c : heap) {
    const RoamNode& n = mesh_.node(c.node);
    if (!n.isLeaf() || n.path != c.path) continue;
    // A constraint: its own error.
    const double px = c.priority >= kForcedPriority ? priorities_.errorPx(view, c.node) : c.priority;
    figures_.achievedErrorPx = std::max(figures_.achievedErrorPx, px);
  }
}

void RoamQueues::lowerDeadline(uint32_t t, double deadline) {
  mesh_.node(t).deadline = std::min(mesh_.node(t).deadline, deadline);
  for (uint32_t u = t; u != kNoNode && mesh_.node(u).subtreeDeadline > deadline; u = mesh_.node(u).parent)
    mesh_.node(u).subtreeDeadline = deadline;
}

std::vector<Candidate> RoamQueues::mergeQueue(std::vector<Candidate>& diamonds, double threshold, bool overBudget) {
  // A diamond's priority is the larger of its two halves'; either half may have been queued
  // (the other's priority, not due, is still on the same side of the bound).
  // Only diamonds below the merge threshold are queued, unless the mesh is over budget.
  auto pairOf = [&](uint32_t t) { return std::min(t, mesh_.node(t).base); };
  std::sort(diamonds.begin(), diamonds.end(),
            [&](const Candidate& a, const Candidate& b) { return pairOf(a.node) < pairOf(b.node); });
  std::vector<Candidate> queue;
  for (size_t i = 0; i < diamonds.size(); ++i) {
    const Candidate& d = diamonds[i];
    if (i > 0 && pairOf(diamonds[i - 1].node) == pairOf(d.node)) continue;  // the pair is in already
    const uint32_t b = mesh_.node(d.node).base;
    const float p = std::max(mesh_.node(d.node).priority, b != kNoNode ? mesh_.node(b).priority : 0.0f);
    if (p < kForcedPriority && (overBudget || p < threshold)) {
      queue.push_back({p, d.node, d.path});
      continue;
    }
    mesh_.cancelMergeMorph(d.node);
    // Held by its partner: look again when either may have changed.
    if (b != kNoNode) lowerDeadline(d.node, mesh_.node(b).deadline);
  }
  std::sort(queue.begin(), queue.end(), [](const Candidate& a, const Candidate& b) {
    return a.priority != b.priority ? a.priority < b.priority : a.node < b.node;
  });
  return queue;
}

void RoamQueues::merge(std::vector<Candidate>& diamonds, double timeS, uint64_t& ops, const Stopwatch& watch) {
  const double threshold = options_.mergeFraction * options_.maxErrorPx;
  const std::vector<Candidate> queue = mergeQueue(diamonds, threshold, mesh_.leafCount() > options_.maxTriangles);
  size_t next = 0;
  for (; next < queue.size(); ++next) {
    const Candidate& c = queue[next];
    if (c.priority >= threshold && mesh_.leafCount() <= options_.maxTriangles) break;
    if (outOfWork(ops, watch)) break;
    const RoamNode& n = mesh_.node(c.node);
    if (n.path != c.path) continue;
    if (!mesh_.isMergeable(c.node)) {  // its partner is split further: until that changes
      if (n.base != kNoNode) lowerDeadline(c.node, mesh_.node(n.base).deadline);
      continue;
    }
    const bool forBudget = c.priority >= threshold;
    if (forBudget) figures_.budgetLimited = true;  // merged for the budget, not the error: at once
    // For the error: the split vertex first sinks to its base over fadeS, then the merge is exact.
    const RoamVertex& mid = mesh_.vertex(n.mid);
    const double fade = mesh_.options().fadeS;
    const bool unseen = c.priority == 0.0f;  // culled: nothing to morph on screen
    if (!forBudget && !unseen && fade > 0.0 && !(mid.merging && mid.morphDone(timeS, fade))) {
      if (!mid.merging) {
        mesh_.beginMergeMorph(c.node);
        ++ops;
        ++figures_.mergesStarted;
      }
      lowerDeadline(c.node, kNow);  // the morph goes on: look again next update
      continue;
    }
    mesh_.merge(c.node);
    ++ops;
    ++figures_.merges;
  }
  // Left for later by the budgets: look again next update.
  for (; next < queue.size(); ++next)
    if (mesh_.node(queue[next].node).path == queue[next].path) lowerDeadline(queue[next].node, kNow);
}

}  // namespace vegstream::terrain
