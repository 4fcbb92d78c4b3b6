// ROAM update: priorities, split and merge queues (roam_tessellator.h). Seed
// 001_3eca9f2c7752e4fb.txt §3.1; Duchaineau et al. 1997 §6 (split/merge queues, budgets).

#include "terrain/roam_tessellator.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <utility>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "core/stopwatch.h"
#include "terrain/roam_error.h"
#include "terrain/roam_walk.h"

namespace vegstream::terrain {

void PieceSet::assign(std::span<const geo::TileId> tiles) {
  tiles_.assign(tiles.begin(), tiles.end());
  index_.clear();
  above_.clear();
  minZoom_ = std::numeric_limits<int>::max();
  maxZoom_ = -1;
  for (size_t i = 0; i < tiles_.size(); ++i) {
    const geo::TileId& t = tiles_[i];
    index_.emplace(pack(t), static_cast<int>(i));
    minZoom_ = std::min(minZoom_, t.z);
    maxZoom_ = std::max(maxZoom_, t.z);
    for (int z = t.z - 1; z >= 0; --z) {
      const int k = t.z - z;
      if (!above_.insert(pack({z, t.x >> k, t.y >> k})).second) break;  // its ancestors are in already
    }
  }
}

int PieceSet::pieceOf(const geo::TileId& square) const {
  // Only the zooms pieces are at: a new leaf asks this, and most pieces are at one or two zooms.
  for (int z = std::min(square.z, maxZoom_); z >= minZoom_; --z) {
    const int k = square.z - z;
    const int i = exactly({z, square.x >> k, square.y >> k});
    if (i >= 0) return i;
  }
  return -1;
}

RoamTessellator::RoamTessellator(BintreeGrid grid, geo::TileRange roots, const geo::LocalFrame& frame,
                                 ResidentHeights& heights, RoamOptions options, SeedOptions seeds,
                                 RoamMeshOptions meshOptions, double seedLatitudeDeg)
    : mesh_(grid, roots, frame, heights, meshOptions), frame_(frame), options_(options), seeds_(seeds),
      seedLevel_(seedLevelFor(grid, seedLatitudeDeg, seeds.targetAreaM2)) {
  mesh_.reserve(options_.maxTriangles);
}

void RoamTessellator::tilesChanged(std::span<const streaming::TileKey> keys) {
  if (keys.empty()) return;
  finishCompaction();
  for (const streaming::TileKey& k : keys)
    if (k.layer == streaming::TileLayer::Height) mesh_.resample(k.id);
}

void RoamTessellator::beginUpdate(const EyeView& view) {
  const Projection projection{view.nearM,    view.pixelsPerRadian, view.tanHalfX,
                              view.tanHalfY, options_.maxErrorPx,  options_.mergeFraction * options_.maxErrorPx};
  evaluateAll_ = !options_.deferPriorities || !(projection == lastProjection_) || !(lastCamera_ == lastCamera_) ||
                 mesh_.leafCount() > options_.maxTriangles;  // over budget: every diamond is a candidate
  lastProjection_ = projection;
  const double moved = lastCamera_ == lastCamera_ ? glm::length(view.cameraEnu - lastCamera_) : 0.0;
  odometerM_ += moved;
  lastCamera_ = view.cameraEnu;
  // The bounds let the vertical turn as the ellipsoid's normal does over the distance moved; a
  // view whose "up" turned more (not the local vertical) has every priority computed again.
  const glm::dvec3 up = glm::transpose(view.rotation) * view.upEye;
  if (glm::dot(up, lastUp_) < std::cos(moved / kMinCurvatureRadiusM) - 1e-12) evaluateAll_ = true;
  lastUp_ = up;
}

double RoamTessellator::sphereDistance(const EyeView& view, uint32_t t, const glm::dvec3* eye, double thickness) const {
  return ErrorGeometry::of(view, eye, thickness, mesh_.node(t).radius).sphereDistance();
}

double RoamTessellator::projectedErrorPx(const EyeView& view, uint32_t t, const glm::dvec3* eye,
                                         double thickness) const {
  return ErrorGeometry::of(view, eye, thickness, mesh_.node(t).radius).errorPx();
}

RoamTessellator::InPiece RoamTessellator::pieceState(const PieceSet& pieces, const geo::TileId& square, InPiece parent,
                                                     int level) const {
  if (level > 0 && (parent != InPiece::Above || level % 2 == 1)) return parent;
  if (pieces.exactly(square) >= 0) return InPiece::In;
  return pieces.isAbove(square) ? InPiece::Above : InPiece::None;
}

RoamTessellator::InPiece RoamTessellator::pieceStateOf(const PieceSet& pieces, uint32_t t) const {
  const geo::TileId square = mesh_.grid().square(mesh_.corners(t), mesh_.node(t).path.level);
  if (pieces.pieceOf(square) >= 0) return InPiece::In;
  return pieces.isAbove(square) ? InPiece::Above : InPiece::None;
}

float RoamTessellator::priority(const EyeView& view, uint32_t t, const glm::dvec3* eye, Cull cull, InPiece ps,
                                ErrorGeometry* geometry) const {
  if (cull == Cull::Outside) return 0.0f;
  if (ps == InPiece::Above) return kForcedPriority;
  const RoamNode& n = mesh_.node(t);
  if (!(n.thickness >= 0.0f)) return 0.0f;  // nothing known yet, or no data under it
  const ErrorGeometry g = ErrorGeometry::of(view, eye, n.thickness, n.radius);
  if (geometry) *geometry = g;
  if (seeds_.refineToSeedLevel && n.path.level < seedLevel_ && g.sphereDistance() < seeds_.horizonM)
    return kForcedPriority;
  return static_cast<float>(g.errorPx());
}

double RoamTessellator::errorPx(const EyeView& view, uint32_t t) const {
  glm::dvec3 eye[3];
  eyeOf(view, t, eye);
  const RoamNode& n = mesh_.node(t);
  if (!(n.thickness >= 0.0f)) return 0.0;
  return projectedErrorPx(view, t, eye, n.thickness);
}

void RoamTessellator::update(const EyeView& view, const PieceSet& pieces, double timeS) {
  Stopwatch watch;
  figures_ = {};
  finishCompaction();
  figures_.compactWaitMs = std::exchange(compactWaitMs_, 0.0);
  mesh_.setTime(timeS);
  timeS_ = timeS;
  beginUpdate(view);
  std::vector<Candidate> splits, diamonds;
  const Frustum frustum(view);
  Walk w;
  w.view = &view;
  w.frustum = &frustum;
  w.pieces = &pieces;
  w.bound = options_.maxErrorPx;
  w.splits = &splits;
  w.diamonds = &diamonds;
  w.mergeBelow = options_.mergeFraction * options_.maxErrorPx;
  w.overBudget = mesh_.leafCount() > options_.maxTriangles;
  const double started = watch.elapsedMs();  // the compaction's wait and beginUpdate before it
  computePriorities(w);
  const double visited = watch.elapsedMs();
  figures_.prioritiesMs = visited - started;
  uint64_t ops = 0;
  splitPhase(w, splits, ops, watch);
  const double split = watch.elapsedMs();
  figures_.splitMs = split - visited;
  mergePhase(diamonds, ops, watch);
  const double merged = watch.elapsedMs();
  figures_.mergeMs = merged - split;
  // The pools are put back in depth-first order (cache locality) once the splits since the last
  // time have allocated 1 / kCompactChurn as many node pairs as are live: that is what scatters
  // them (a compaction costs milliseconds, so it waits for churn, not for a number of frames).
  // At the end of the update: with a task runner its copy goes on beside the output and the rest
  // of the frame, and the next update applies it; without one, this update makes it and this
  // frame's output walks the compacted pools.
  const bool compact = mesh_.pairsAllocatedSinceCompact() * kCompactChurn >= mesh_.livePairs();
  if (++updates_ % kChunkIdleFrames == 0 || compact) {
    releaseChunks();
    dropIdleChunks();
  }
  if (compact) {
    startCompaction();
    figures_.compacted = true;
  }
  figures_.compactMs = watch.elapsedMs() - merged;
  figures_.leaves = mesh_.leafCount();
  figures_.updateMs = watch.elapsedMs();
}

bool RoamTessellator::outOfWork(uint64_t ops, const Stopwatch& watch) {
  if (ops >= options_.maxOpsPerFrame || (options_.maxQueueMs > 0.0 && watch.elapsedMs() > options_.maxQueueMs)) {
    figures_.workLimited = true;
    return true;
  }
  return false;
}

void RoamTessellator::splitPhase(const Walk& w, std::vector<Candidate>& heap, uint64_t& ops, const Stopwatch& watch) {
  const EyeView& view = *w.view;
  const PieceSet& pieces = *w.pieces;
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
      const RoamNode& ln = mesh_.node(leaf);
      if (!ln.isLeaf()) continue;
      glm::dvec3 eye[3];
      eyeOf(view, leaf, eye);
      const double e = ln.cullThickness();
      const Cull cull = cullWedgie(*w.frustum, eye[0], eye[1], eye[2], e, e + options_.canopyM);
      PriorityFigures counts;
      evaluateLeaf(view, leaf, eye, cull, pieceStateOf(pieces, leaf), counts);
      figures_.prioritiesComputed += counts.computed;
      figures_.achievedErrorPx = std::max(figures_.achievedErrorPx, counts.achievedErrorPx);
      RoamNode& evaluated = mesh_.node(leaf);
      evaluated.subtreeDeadline = evaluated.deadline;  // its ancestors are due already (the split)
      const float p = evaluated.priority;
      if (p > bound) {
        heap.push_back({p, leaf, ln.path});
        std::push_heap(heap.begin(), heap.end(), less);
      }
    }
  }
  // What the budgets left unsplit is what the mesh misses the bound by.
  for (const Candidate& c : heap) {
    const RoamNode& n = mesh_.node(c.node);
    if (!n.isLeaf() || n.path != c.path) continue;
    double px = c.priority;
    if (c.priority >= kForcedPriority) {  // a constraint: its own error
      glm::dvec3 eye[3];
      eyeOf(view, c.node, eye);
      px = n.thickness >= 0.0f ? projectedErrorPx(view, c.node, eye, n.thickness) : 0.0;
    }
    figures_.achievedErrorPx = std::max(figures_.achievedErrorPx, px);
  }
}

void RoamTessellator::lowerDeadline(uint32_t t, double deadline) {
  mesh_.node(t).deadline = std::min(mesh_.node(t).deadline, deadline);
  for (uint32_t u = t; u != kNoNode && mesh_.node(u).subtreeDeadline > deadline; u = mesh_.node(u).parent)
    mesh_.node(u).subtreeDeadline = deadline;
}

void RoamTessellator::mergePhase(std::vector<Candidate>& diamonds, uint64_t& ops, const Stopwatch& watch) {
  // A diamond's priority is the larger of its two halves'; either half may have been queued
  // (the other's priority, not due, is still on the same side of the bound).
  // Only diamonds below the merge threshold are queued, unless the mesh is over budget.
  const double threshold = options_.mergeFraction * options_.maxErrorPx;
  const bool overBudget = mesh_.leafCount() > options_.maxTriangles;
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
    if (!forBudget && !unseen && fade > 0.0 && !(mid.merging && mid.morphDone(timeS_, fade))) {
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
