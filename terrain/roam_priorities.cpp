// RoamPriorities (roam_priorities.h): ROAM update, step 1, the priority traversal. Seed
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

#include "terrain/roam_priorities.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "core/parallel_for.h"
#include "terrain/roam_error.h"

namespace vegstream::terrain {

struct RoamPriorities::Walk {
  const EyeView* view = nullptr;
  const Frustum* frustum = nullptr;  // the view's planes
  const PieceSet* pieces = nullptr;
  double bound = 0.0;
  std::vector<Candidate>* splits = nullptr;
  std::vector<Candidate>* diamonds = nullptr;
  double mergeBelow = 0.0;
  bool overBudget = false;
  PriorityFigures counts;
  std::vector<uint32_t>* cancels = nullptr;  // diamonds whose merge morph is cancelled after the traversal
  // The top of a parallel traversal (compute): the subtrees handed to tasks, and the nodes above
  // them, post-order, whose subtree deadlines wait for the tasks.
  std::vector<PriorityTask>* tasks = nullptr;
  size_t taskCount = 0;
  std::vector<uint32_t> waiting;
};

void PriorityFigures::add(const PriorityFigures& o) {
  visited += o.visited;
  computed += o.computed;
  achievedErrorPx = std::max(achievedErrorPx, o.achievedErrorPx);
}

RoamPriorities::RoamPriorities(RoamMesh& mesh, const RoamOptions& options, const SeedOptions& seeds, int seedLevel)
    : mesh_(mesh), options_(options), seeds_(seeds), seedLevel_(seedLevel) {}

void RoamPriorities::begin(const EyeView& view) {
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

InPiece RoamPriorities::pieceState(const PieceSet& pieces, const geo::TileId& square, InPiece parent, int level) const {
  if (level > 0 && (parent != InPiece::Above || level % 2 == 1)) return parent;
  if (pieces.exactly(square) >= 0) return InPiece::In;
  return pieces.isAbove(square) ? InPiece::Above : InPiece::None;
}

InPiece RoamPriorities::pieceStateOf(const PieceSet& pieces, uint32_t t) const {
  const geo::TileId square = mesh_.grid().square(mesh_.corners(t), mesh_.node(t).path.level);
  if (pieces.pieceOf(square) >= 0) return InPiece::In;
  return pieces.isAbove(square) ? InPiece::Above : InPiece::None;
}

float RoamPriorities::priority(const EyeView& view, uint32_t t, const glm::dvec3* eye, Cull cull, InPiece ps,
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

double RoamPriorities::errorPx(const EyeView& view, uint32_t t) const {
  glm::dvec3 eye[3];
  eyeOf(mesh_, view, t, eye);
  const RoamNode& n = mesh_.node(t);
  if (!(n.thickness >= 0.0f)) return 0.0;
  return ErrorGeometry::of(view, eye, n.thickness, n.radius).errorPx();
}

void RoamPriorities::compute(const EyeView& view, const Frustum& frustum, const PieceSet& pieces,
                             std::vector<Candidate>& splits, std::vector<Candidate>& diamonds, RoamFigures& figures) {
  Walk w;
  w.view = &view;
  w.frustum = &frustum;
  w.pieces = &pieces;
  w.bound = options_.maxErrorPx;
  w.splits = &splits;
  w.diamonds = &diamonds;
  w.mergeBelow = options_.mergeFraction * options_.maxErrorPx;
  w.overBudget = mesh_.leafCount() > options_.maxTriangles;
  std::vector<uint32_t> cancels;
  w.cancels = &cancels;
  w.tasks = options_.tasks ? &tasks_ : nullptr;
  for (uint32_t r : mesh_.roots()) {
    glm::dvec3 eye[3];
    eyeOf(mesh_, view, r, eye);
    descend(w, r, eye, Cull::Partial, kEveryPlane, InPiece::None);
  }
  if (w.taskCount > 0) runTasks(w, cancels);
  // The nodes above the tasks, children first.
  for (uint32_t t : w.waiting) {
    RoamNode& n = mesh_.node(t);
    n.subtreeDeadline =
        std::min({n.deadline, mesh_.node(n.child).subtreeDeadline, mesh_.node(n.child + 1).subtreeDeadline});
  }
  // Cancelling is idempotent and writes nothing the traversal reads: done after it, in any
  // order, it gives what cancelling on the way gave.
  for (uint32_t t : cancels) mesh_.cancelMergeMorph(t);
  figures.priorityTasks = w.taskCount;
  figures.nodesVisited = w.counts.visited;
  figures.prioritiesComputed = w.counts.computed;
  figures.achievedErrorPx = w.counts.achievedErrorPx;
}

void RoamPriorities::runTasks(Walk& w, std::vector<uint32_t>& cancels) {
  const auto run = [&](size_t k) -> Status {
    PriorityTask& task = tasks_[k];
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
    visit(tw, task.node, task.cull == Cull::Outside ? nullptr : task.eye, task.cull, task.planes, task.ps);
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
    const PriorityTask& task = tasks_[k];
    w.splits->insert(w.splits->end(), task.splits.begin(), task.splits.end());
    w.diamonds->insert(w.diamonds->end(), task.diamonds.begin(), task.diamonds.end());
    cancels.insert(cancels.end(), task.cancels.begin(), task.cancels.end());
    w.counts.add(task.counts);
  }
}

void RoamPriorities::descend(Walk& w, uint32_t t, const glm::dvec3* eye, Cull cull, PlaneMask planes, InPiece ps) {
  if (!w.tasks || mesh_.node(t).leafCount > kTaskLeaves) {
    visit(w, t, eye, cull, planes, ps);
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

void RoamPriorities::visit(Walk& w, uint32_t t, const glm::dvec3* eye, Cull cull, PlaneMask planes, InPiece ps) {
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
  visitChildren(w, t, eye, cull, planes, ps);
}

void RoamPriorities::visitChildren(Walk& w, uint32_t t, const glm::dvec3* eye, Cull cull, PlaneMask planes,
                                   InPiece ps) {
  const uint32_t c = mesh_.node(t).child;
  // Children the deferral skips on entry (the test at the top of visit, for a cull and piece
  // state they inherit unchanged) need no eye coordinates: do not transform the split vertex
  // for them.
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
      const glm::dvec3 m = eyeOfVertex(mesh_, *w.view, mesh_.node(t).mid);
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
      if (!skip0) descend(w, c, e0, cull, planes, ps);
      if (!skip1) descend(w, c + 1, e1, cull, planes, ps);
    } else {
      if (!skip0) visit(w, c, e0, cull, planes, ps);
      if (!skip1) visit(w, c + 1, e1, cull, planes, ps);
    }
  }
  if (top) {
    w.waiting.push_back(t);
    return;
  }
  RoamNode& after = mesh_.node(t);
  after.subtreeDeadline = std::min({after.deadline, mesh_.node(c).subtreeDeadline, mesh_.node(c + 1).subtreeDeadline});
}

float RoamPriorities::evaluateNewLeaf(const EyeView& view, const Frustum& frustum, const PieceSet& pieces,
                                      uint32_t leaf, RoamFigures& figures) {
  glm::dvec3 eye[3];
  eyeOf(mesh_, view, leaf, eye);
  const double e = mesh_.node(leaf).cullThickness();
  const Cull cull = cullWedgie(frustum, eye[0], eye[1], eye[2], e, e + options_.canopyM);
  PriorityFigures counts;
  evaluateLeaf(view, leaf, eye, cull, pieceStateOf(pieces, leaf), counts);
  figures.prioritiesComputed += counts.computed;
  figures.achievedErrorPx = std::max(figures.achievedErrorPx, counts.achievedErrorPx);
  RoamNode& evaluated = mesh_.node(leaf);
  evaluated.subtreeDeadline = evaluated.deadline;  // its ancestors are due already (the split)
  return evaluated.priority;
}

void RoamPriorities::evaluateLeaf(const EyeView& view, uint32_t t, const glm::dvec3* eye, Cull cull, InPiece ps,
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

void RoamPriorities::evaluateDiamond(Walk& w, uint32_t t, const glm::dvec3* eye, Cull cull, InPiece ps) {
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
