// ROAM update: priorities, split and merge queues (roam_tessellator.h). Seed
// 001_3eca9f2c7752e4fb.txt §3.1; Duchaineau et al. 1997 §6 (split/merge queues, budgets).

#include "terrain/roam_tessellator.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include <glm/geometric.hpp>

#include "core/stopwatch.h"
#include "terrain/roam_walk.h"

namespace vegstream::terrain {

void PieceSet::assign(std::span<const geo::TileId> tiles) {
  tiles_.assign(tiles.begin(), tiles.end());
  index_.clear();
  above_.clear();
  for (size_t i = 0; i < tiles_.size(); ++i) {
    const geo::TileId& t = tiles_[i];
    index_.emplace(pack(t), static_cast<int>(i));
    for (int z = t.z - 1; z >= 0; --z) {
      const int k = t.z - z;
      if (!above_.insert(pack({z, t.x >> k, t.y >> k})).second) break;  // its ancestors are in already
    }
  }
}

int PieceSet::pieceOf(const geo::TileId& square) const {
  for (int z = square.z; z >= 0; --z) {
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
      seedLevel_(seedLevelFor(grid, seedLatitudeDeg, seeds.targetAreaM2)) {}

void RoamTessellator::tilesChanged(std::span<const streaming::TileKey> keys) {
  for (const streaming::TileKey& k : keys)
    if (k.layer == streaming::TileLayer::Height) mesh_.resample(k.id);
}

void RoamTessellator::beginView(const EyeView& view) {
  if (view.cameraEnu == lastCamera_ && view.rotation == lastRotation_) return;
  lastCamera_ = view.cameraEnu;
  lastRotation_ = view.rotation;
  ++viewId_;
}

glm::dvec3 RoamTessellator::eyeOfVertex(const EyeView& view, uint32_t v) const {
  // Each vertex is transformed once per view (§3.1 A: only a split's new vertex is new).
  if (v >= eyes_.size()) eyes_.resize(mesh_.vertexCapacity() + 1024);
  EyeEntry& e = eyes_[v];
  if (e.view != viewId_) {
    e.eye = view.toEye(mesh_.vertex(v).at);
    e.view = viewId_;
  }
  return e.eye;
}

void RoamTessellator::eyeOf(const EyeView& view, uint32_t t, glm::dvec3* eye) const {
  const RoamNode& n = mesh_.node(t);
  for (int i = 0; i < 3; ++i) eye[i] = eyeOfVertex(view, n.v[i]);
}

double RoamTessellator::sphereDistance(const EyeView& view, uint32_t t, const glm::dvec3* eye, double thickness) const {
  // The hypotenuse midpoint is the circumcentre of a right triangle (in the plane); heights make
  // the radius the larger of the two distances (RoamNode::radius, rotation-invariant).
  const glm::dvec3 c = 0.5 * (eye[1] + eye[2]);
  return std::max(glm::length(c) - mesh_.node(t).radius - thickness, view.nearM);
}

double RoamTessellator::projectedErrorPx(const EyeView& view, uint32_t t, const glm::dvec3* eye, double thickness) const {
  // The wedgie's thickness is vertical: seen along a ray at angle θ to the vertical it spans
  // e·sin θ / d radians (Duchaineau et al. project the thickness vector the same way). Over the
  // bounding sphere θ is within θ_c ± α, sin α = radius / ‖c‖, and sin(θ_c + α) ≤ sin θ_c + sin α.
  const glm::dvec3 c = 0.5 * (eye[1] + eye[2]);
  const double r = mesh_.node(t).radius + thickness;
  const double dc = glm::length(c);
  const double d = std::max(dc - r, view.nearM);
  double sinMax = 1.0;
  if (dc > r) {
    const double cosC = std::abs(glm::dot(view.upEye, c)) / dc;
    sinMax = std::min(1.0, std::sqrt(std::max(0.0, 1.0 - cosC * cosC)) + r / dc);
  }
  return thickness * sinMax * view.pixelsPerRadian / d;
}

RoamTessellator::InPiece RoamTessellator::pieceState(const PieceSet& pieces, const geo::TileId& square,
                                                     InPiece parent, int level) const {
  if (level > 0 && (parent != InPiece::Above || level % 2 == 1)) return parent;
  if (pieces.exactly(square) >= 0) return InPiece::In;
  return pieces.isAbove(square) ? InPiece::Above : InPiece::None;
}

RoamTessellator::InPiece RoamTessellator::pieceStateOf(const PieceSet& pieces, uint32_t t) const {
  const geo::TileId square = mesh_.grid().square(mesh_.corners(t), mesh_.node(t).path.level);
  if (pieces.pieceOf(square) >= 0) return InPiece::In;
  return pieces.isAbove(square) ? InPiece::Above : InPiece::None;
}

float RoamTessellator::priority(const EyeView& view, uint32_t t, const glm::dvec3* eye, Cull cull,
                                InPiece ps) const {
  if (cull == Cull::Outside) return 0.0f;
  if (ps == InPiece::Above) return kForcedPriority;
  const RoamNode& n = mesh_.node(t);
  if (!(n.thickness >= 0.0f)) return 0.0f;  // nothing known yet, or no data under it
  if (seeds_.refineToSeedLevel && n.path.level < seedLevel_ && sphereDistance(view, t, eye, n.thickness) < seeds_.horizonM)
    return kForcedPriority;
  return static_cast<float>(projectedErrorPx(view, t, eye, n.thickness));
}

double RoamTessellator::errorPx(const EyeView& view, uint32_t t) const {
  glm::dvec3 eye[3];
  eyeOf(view, t, eye);
  const RoamNode& n = mesh_.node(t);
  if (!(n.thickness >= 0.0f)) return 0.0;
  return projectedErrorPx(view, t, eye, n.thickness);
}

void RoamTessellator::visitPriorities(Walk& w, uint32_t t, const glm::dvec3* eye, Cull cull, InPiece ps) {
  RoamNode& n = mesh_.node(t);
  const int level = n.path.level;
  if (cull == Cull::Partial) {
    const double e = std::max(0.0f, n.thickness == n.thickness ? n.thickness : 0.0f);
    cull = cullWedgie(*w.view, eye[0], eye[1], eye[2], e, e + options_.canopyM);
  }
  if (level == 0 || (ps == InPiece::Above && level % 2 == 0))
    ps = pieceState(*w.pieces, mesh_.grid().square(mesh_.corners(t), level), ps, level);
  if (n.isLeaf()) {
    n.priority = priority(*w.view, t, eye, cull, ps);
    if (n.priority > w.bound) w.splits->push_back({n.priority, t, n.path});
    return;
  }
  const uint32_t c = n.child;
  if (mesh_.node(c).isLeaf() && mesh_.node(c + 1).isLeaf()) {
    n.priority = priority(*w.view, t, eye, cull, ps);
    // A diamond merges below the threshold (its priority is the larger half's), or for the budget.
    if (n.priority < w.mergeBelow || w.overBudget) w.diamonds->push_back({n.priority, t, n.path});
    else mesh_.cancelMergeMorph(t);  // it sank towards a merge that is no longer wanted
  } else {
    n.priority = kForcedPriority;  // not a diamond half: never merged as one
    mesh_.cancelMergeMorph(t);
  }
  glm::dvec3 e0[3], e1[3];
  if (cull != Cull::Outside) {
    const glm::dvec3 m = eyeOfVertex(*w.view, n.mid);
    e0[0] = m; e0[1] = eye[0]; e0[2] = eye[1];
    e1[0] = m; e1[1] = eye[2]; e1[2] = eye[0];
  }
  visitPriorities(w, c, e0, cull, ps);
  visitPriorities(w, c + 1, e1, cull, ps);
}

void RoamTessellator::update(const EyeView& view, const PieceSet& pieces, double timeS) {
  Stopwatch watch;
  figures_ = {};
  mesh_.setTime(timeS);
  timeS_ = timeS;
  // Every kCompactEvery updates the pools are put back in depth-first order (cache locality).
  if (++updates_ % kCompactEvery == 0) {
    mesh_.compact();
    eyes_.clear();
    stamps_.clear();
  }
  beginView(view);
  std::vector<Candidate> splits, diamonds;
  Walk w;
  w.view = &view;
  w.pieces = &pieces;
  w.bound = options_.maxErrorPx;
  w.splits = &splits;
  w.diamonds = &diamonds;
  w.mergeBelow = options_.mergeFraction * options_.maxErrorPx;
  w.overBudget = mesh_.leafCount() > options_.maxTriangles;
  for (uint32_t r : mesh_.roots()) {
    glm::dvec3 eye[3];
    eyeOf(view, r, eye);
    visitPriorities(w, r, eye, Cull::Partial, InPiece::None);
  }
  uint64_t ops = 0;
  splitPhase(view, pieces, splits, ops, watch);
  mergePhase(diamonds, ops, watch);
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

void RoamTessellator::splitPhase(const EyeView& view, const PieceSet& pieces, std::vector<Candidate>& heap,
                                 uint64_t& ops, const Stopwatch& watch) {
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
    if (!mesh_.split(c.node, &created)) continue;  // at the deepest level
    ++ops;
    ++figures_.splits;
    // The new leaves (the diamond's and the forced splits') may need more splits this frame.
    for (uint32_t leaf : created) {
      const RoamNode& ln = mesh_.node(leaf);
      if (!ln.isLeaf()) continue;
      glm::dvec3 eye[3];
      eyeOf(view, leaf, eye);
      const double e = std::max(0.0f, ln.thickness == ln.thickness ? ln.thickness : 0.0f);
      const Cull cull = cullWedgie(view, eye[0], eye[1], eye[2], e, e + options_.canopyM);
      const float p = priority(view, leaf, eye, cull, pieceStateOf(pieces, leaf));
      mesh_.node(leaf).priority = p;
      if (p > bound) {
        heap.push_back({p, leaf, ln.path});
        std::push_heap(heap.begin(), heap.end(), less);
      }
    }
  }
}

void RoamTessellator::mergePhase(std::vector<Candidate>& diamonds, uint64_t& ops, const Stopwatch& watch) {
  // A diamond's priority is the larger of its two halves'.
  // Only diamonds below the merge threshold are queued, unless the mesh is over budget.
  const double threshold = options_.mergeFraction * options_.maxErrorPx;
  const bool overBudget = mesh_.leafCount() > options_.maxTriangles;
  std::vector<Candidate> queue;
  for (const Candidate& d : diamonds) {
    const uint32_t b = mesh_.node(d.node).base;
    if (b != kNoNode && b < d.node) continue;  // the partner with the smaller index speaks for both
    const float p = std::max(d.priority, b != kNoNode ? mesh_.node(b).priority : 0.0f);
    if (p < kForcedPriority && (overBudget || p < threshold)) queue.push_back({p, d.node, d.path});
    else mesh_.cancelMergeMorph(d.node);
  }
  std::sort(queue.begin(), queue.end(), [](const Candidate& a, const Candidate& b) {
    return a.priority != b.priority ? a.priority < b.priority : a.node < b.node;
  });
  for (const Candidate& c : queue) {
    if (c.priority >= threshold && mesh_.leafCount() <= options_.maxTriangles) break;
    if (outOfWork(ops, watch)) break;
    const RoamNode& n = mesh_.node(c.node);
    if (n.path != c.path || !mesh_.isMergeable(c.node)) continue;
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
      continue;
    }
    mesh_.merge(c.node);
    ++ops;
    ++figures_.merges;
  }
}

}  // namespace vegstream::terrain
