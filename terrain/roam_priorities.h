#pragma once
// RoamPriorities (internal to the tessellator, roam_tessellator.h update(), step 1): every
// leaf's and diamond's priority — the projected wedgie thickness in px (roam_error.h), 0 outside
// the view, kForcedPriority under a constraint — computed by one traversal with hierarchical
// culling, deferred (Duchaineau et al. 1997 §6): it owns the camera's odometer and what a change
// of which means every priority is computed again (the projection, the bound, the vertical),
// and the subtrees it hands to RoamOptions::tasks.
//
// Contract:
//   - begin() once per update, then compute(): the split candidates (leaves above the bound)
//     and the merge candidates (diamonds below mergeFraction × the bound, all of them when the
//     mesh is over budget) in traversal order — the same order with or without tasks — and
//     each node's priority, deadline (an odometer reading) and subtree deadline. A priority is
//     computed again only when due (roam_mesh.h RoamNode::deadline), or its cull or piece state
//     changed; a subtree none of whose priorities is due and wholly in (or out of) the view and
//     the pieces as before is not visited.
//   - evaluateNewLeaf(): a leaf the split queue just made, computed at once.
// Writes the nodes' priority fields only (and cancels merge morphs no longer wanted).

#include <cstdint>
#include <limits>
#include <vector>

#include <glm/vec3.hpp>

#include "terrain/eye_space.h"
#include "terrain/roam_mesh.h"
#include "terrain/roam_tessellator.h"

namespace vegstream::terrain {

struct ErrorGeometry;  // roam_error.h

// Deadlines (RoamNode::deadline): never due until the cull, piece or mesh changes; due now.
inline constexpr double kNever = std::numeric_limits<double>::infinity();
inline constexpr double kNow = -std::numeric_limits<double>::infinity();

// Where a node stands against the pieces: outside every one, above one (it must split), in one.
enum class InPiece : uint8_t { None, Above, In };

// A split or merge candidate: a node, its path when queued (it may be gone since) and priority.
struct Candidate {
  float priority;
  uint32_t node;
  TriPath path;
};

struct PriorityFigures {
  uint64_t visited = 0, computed = 0;
  double achievedErrorPx = 0.0;
  void add(const PriorityFigures& o);
};

class RoamPriorities {
 public:
  // Every reference outlives this; `options` is read live (RoamTessellator::setMaxErrorPx).
  RoamPriorities(RoamMesh& mesh, const RoamOptions& options, const SeedOptions& seeds, int seedLevel);

  // The odometer moves with the camera; whether this update computes every priority again.
  void begin(const EyeView& view);
  // The traversal: candidates in traversal order into `splits` and `diamonds` (empty before);
  // priorityTasks, nodesVisited, prioritiesComputed and achievedErrorPx into `figures`.
  void compute(const EyeView& view, const Frustum& frustum, const PieceSet& pieces, std::vector<Candidate>& splits,
               std::vector<Candidate>& diamonds, RoamFigures& figures);
  // A leaf made by a split this update: its priority (returned), deadline and subtree deadline;
  // prioritiesComputed and achievedErrorPx into `figures`.
  float evaluateNewLeaf(const EyeView& view, const Frustum& frustum, const PieceSet& pieces, uint32_t leaf,
                        RoamFigures& figures);
  // Priority (px) a node would have for `view`, its constraints ignored.
  double errorPx(const EyeView& view, uint32_t t) const;

 private:
  struct Walk;  // the state of one traversal
  // A subtree handed to a task: where it starts, and what it gives back.
  struct PriorityTask {
    uint32_t node;
    glm::dvec3 eye[3];  // unset when culled: an Outside subtree needs none
    Cull cull;
    PlaneMask planes;  // those its wedgie straddles, when Partial
    InPiece ps;
    std::vector<Candidate> splits, diamonds;
    std::vector<uint32_t> cancels;
    PriorityFigures counts;
  };
  static constexpr uint32_t kTaskLeaves = 1024;  // ≥ 2: a task's root is never a leaf or diamond of the top

  // geometry (optional) receives the error geometry when the priority came from it.
  float priority(const EyeView& view, uint32_t t, const glm::dvec3* eye, Cull cull, InPiece ps,
                 ErrorGeometry* geometry = nullptr) const;
  InPiece pieceState(const PieceSet& pieces, const geo::TileId& square, InPiece parent, int level) const;
  InPiece pieceStateOf(const PieceSet& pieces, uint32_t t) const;
  void runTasks(Walk& w, std::vector<uint32_t>& cancels);
  // `planes`: those the parent's wedgie straddles, when `cull` is Partial (eye_space.h).
  void descend(Walk& w, uint32_t t, const glm::dvec3* eye, Cull cull, PlaneMask planes, InPiece ps);
  void visit(Walk& w, uint32_t t, const glm::dvec3* eye, Cull cull, PlaneMask planes, InPiece ps);
  void visitChildren(Walk& w, uint32_t t, const glm::dvec3* eye, Cull cull, PlaneMask planes, InPiece ps);
  void evaluateLeaf(const EyeView& view, uint32_t t, const glm::dvec3* eye, Cull cull, InPiece ps,
                    PriorityFigures& counts);
  void evaluateDiamond(Walk& w, uint32_t t, const glm::dvec3* eye, Cull cull, InPiece ps);

  RoamMesh& mesh_;
  const RoamOptions& options_;
  const SeedOptions& seeds_;
  const int seedLevel_;
  std::vector<PriorityTask> tasks_;  // reused: their vectors keep their capacity
  double odometerM_ = 0.0;           // metres the camera travelled
  glm::dvec3 lastCamera_{std::numeric_limits<double>::quiet_NaN()};
  glm::dvec3 lastUp_{0.0};
  struct Projection {
    double nearM = 0.0, pixelsPerRadian = 0.0, tanHalfX = 0.0, tanHalfY = 0.0, boundPx = 0.0, mergePx = 0.0;
    auto operator<=>(const Projection&) const = default;
  } lastProjection_;
  bool evaluateAll_ = true;  // this update computes every priority again
};

}  // namespace vegstream::terrain
