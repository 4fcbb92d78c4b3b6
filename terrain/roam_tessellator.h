#pragma once
// ROAM over the streamed tiles (seed 001_3eca9f2c7752e4fb.txt §3.1; Duchaineau et al. 1997):
// each frame the persistent bintree (roam_mesh.h) is split and merged towards the triangulation
// whose on-screen error is within `maxErrorPx` under a triangle budget — frame-to-frame
// coherent, never rebuilt — and then traversed once more to emit what is drawn and the seed
// triangles.
//
// update():
//   1. one traversal computes every leaf's priority (projected wedgie thickness, px: the nested
//      thickness · sin(the largest angle between the vertical and a view ray to the triangle's
//      bounding sphere) · pixels-per-radian / distance to that sphere) with
//      hierarchical culling (a leaf outside the view has priority 0, so it merges away), and the
//      priority of every diamond whose four children are leaves;
//   2. the split queue (max first) splits leaves above the bound, forcing splits as needed, and
//      re-queues their children, until the bound is met, the triangle budget is reached or the
//      per-frame work budget is spent (operations, and optionally milliseconds);
//   3. the merge queue (min first) merges diamonds below mergeFraction × the bound — after their
//      split vertex has sunk to its base over fadeS, so merges do not pop — and, at once, more
//      while the mesh is over budget.
//   Deferred: a priority is computed again only when the camera may have carried it across
//   the split bound (a leaf) or the merge bound (a diamond) — bounds on how far the distance and
//   the viewing angle can change over the metres travelled since — or when its cull or piece
//   state, the mesh under it, the projection or the bound changed. A subtree none of whose
//   priorities is due, entirely inside or outside the view as before, is not visited at all.
//   Two constraints force splits regardless of error: every drawn leaf lies inside one piece
//   (the imagery tile it is coloured from), and, inside the seeding horizon, leaves reach the
//   seed level so that seed triangles have sampled heights.
// output(): the drawn leaves in eye space with hierarchical culling of the wedgie plus the canopy
//   (the tallest plant, so no triangle whose plants can be seen is culled), grouped into one mesh
//   per piece; and the seed triangles (seed_triangles.h): the visible triangles of the seed
//   level within the horizon and facing the camera, their plant counts by eq. 1 or 2. Eye-space
//   coordinates are carried down the recursion: only each split's new vertex is transformed,
//   and refined seed triangles interpolate their parents' (§3.1 A and B).
//
// Deterministic: with maxQueueMs = 0 the same inputs give the same mesh, with or without
// RoamOptions::tasks. Called on the frame thread only; with tasks, parts of the work run on them
// (the output's chunks, done when output() returns; the compaction's copy, waited for later).

#include <cstdint>
#include <deque>
#include <limits>
#include <memory>
#include <span>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "core/stopwatch.h"
#include "core/task_runner.h"
#include "geo/local_frame.h"
#include "streaming/tile_key.h"
#include "terrain/eye_space.h"
#include "terrain/roam_mesh.h"
#include "terrain/seed_triangles.h"
#include "terrain/terrain_mesh.h"

namespace vegstream::terrain {

// The tessellator's parts (internal to terrain/, each in its own header and file).
class RoamPriorities;
class RoamQueues;
class RoamOutput;
class RoamCompactor;

// Priority of a leaf that must split whatever its error (a constraint).
inline constexpr float kForcedPriority = 3.0e38f;

struct RoamOptions {
  double maxErrorPx = 2.0;          // screen-space error bound
  uint64_t maxTriangles = 120000;   // leaves in the mesh (the constraints may exceed it)
  double mergeFraction = 0.6;       // merge diamonds whose priority is below this × the bound
  uint64_t maxOpsPerFrame = 60000;  // splits + merges per frame (a deterministic work budget)
  double maxQueueMs = 0.0;          // a time budget for the queue work; 0: none (deterministic)
  double canopyM = 30.0;            // the tallest plant: wedgies grow by it for culling
  bool cacheChunks = true;          // output: append unchanged drawn chunks as cached (roam_chunks.h)
  bool deferPriorities = true;      // update: compute a priority only when it may have crossed a bound
  // The most leaves a drawn chunk holds: larger chunks are fewer (less work per frame, fewer
  // draws) but each change rebuilds more.
  uint32_t chunkMaxLeaves = 64;
  // Where a compaction's copy runs (RoamMesh::compact): started at the end of the update that
  // calls for it, it goes on beside the output and the rest of the frame, and the next change
  // of the mesh waits for it (or makes the copy itself if no worker has taken it yet). The
  // update's priority subtrees and the output's work per chunk run there too, the frame thread
  // taking its share (parallelFor).
  // Null: all of it on the frame thread. The mesh and the output are the same either way.
  TaskRunner* tasks = nullptr;
};

// The pieces the frame draws: one tile each (at most the dataset's max zoom), none an ancestor
// of another. Every drawn leaf lies inside exactly one of them.
class PieceSet {
 public:
  void assign(std::span<const geo::TileId> tiles);
  const std::vector<geo::TileId>& tiles() const { return tiles_; }
  // Index of the piece that is `square` or contains it; −1 when none does.
  int pieceOf(const geo::TileId& square) const;
  // True when a piece lies strictly inside `square`.
  bool isAbove(const geo::TileId& square) const { return above_.count(pack(square)) != 0; }
  int exactly(const geo::TileId& square) const {
    auto it = index_.find(pack(square));
    return it == index_.end() ? -1 : it->second;
  }
  static uint64_t pack(const geo::TileId& t) {
    return (uint64_t(t.z) << 58) | (uint64_t(uint32_t(t.x)) << 29) | uint64_t(uint32_t(t.y));
  }

 private:
  std::vector<geo::TileId> tiles_;
  std::unordered_map<uint64_t, int> index_;
  std::unordered_set<uint64_t> above_;
  int minZoom_ = 0, maxZoom_ = -1;  // of the pieces (none: an empty range)
};

struct RoamFigures {
  uint64_t leaves = 0;          // triangles in the mesh
  uint64_t drawnTriangles = 0;  // leaves drawn (visible, with data)
  uint64_t splits = 0, merges = 0;
  uint64_t leavesCreated = 0;  // by the splits, forced ones included
  uint64_t nodesVisited = 0;   // the update's traversal (deferral skips subtrees none of whose priorities is due)
  uint64_t priorityTasks = 0;  // subtrees of that traversal handed to RoamOptions::tasks
  uint64_t prioritiesComputed = 0;
  uint64_t mergesStarted = 0;      // diamonds whose split vertex began sinking to its base (merged after fadeS)
  uint64_t constrainedLeaves = 0;  // drawn leaves still coarser than a piece (drawn untextured)
  uint64_t morphingVertices = 0;   // drawn vertices still on their way to a new height
  bool compacted = false;          // the pools were put back in depth-first order (RoamMesh::compact)
  double compactWaitMs = 0.0;      // of updateMs: waiting for the last compaction's copy (RoamOptions::tasks)
  bool budgetLimited = false;      // the triangle budget stopped refinement
  bool workLimited = false;        // the per-frame work budget stopped the queues
  // The largest on-screen error of a visible leaf whose priority the update computed (the
  // others were below the bound and cannot have crossed it: so it exceeds the bound exactly
  // when the mesh does), after the splits.
  double achievedErrorPx = 0.0;
  uint64_t depthLimitedLeaves = 0;             // visible leaves over the bound at the deepest level (cannot split)
  uint64_t chunksReused = 0, chunksBuilt = 0;  // output: drawn chunks handed out as cached, and rebuilt
  uint64_t chunksMoved = 0;                    // of the reused: with vertices still morphing (a new version)
  uint64_t leavesEmitted = 0;  // output: leaves turned into vertices this frame (the rest came from chunks)
  uint64_t seedTriangles = 0;
  uint64_t seedInterpolated = 0;  // seed triangles refined below a coarser leaf
  double seedPlants = 0.0;        // Σ plant counts
  double updateMs = 0.0, outputMs = 0.0;
  // Where the update's time went: compaction, the priority traversal, the split and merge queues.
  double compactMs = 0.0, prioritiesMs = 0.0, splitMs = 0.0, mergeMs = 0.0;
};

class RoamTessellator {
 public:
  RoamTessellator(BintreeGrid grid, geo::TileRange roots, const geo::LocalFrame& frame, ResidentHeights& heights,
                  RoamOptions options, SeedOptions seeds, RoamMeshOptions meshOptions, double seedLatitudeDeg);

  ~RoamTessellator();
  RoamTessellator(const RoamTessellator&) = delete;
  RoamTessellator& operator=(const RoamTessellator&) = delete;

  RoamMesh& mesh() {
    finishCompaction();
    return mesh_;
  }
  const RoamMesh& mesh() const { return mesh_; }
  const RoamOptions& options() const { return options_; }
  void setMaxErrorPx(double px) { options_.maxErrorPx = px; }
  int seedLevel() const { return seedLevel_; }
  const BintreeGrid& grid() const { return mesh_.grid(); }
  const SeedOptions& seedOptions() const { return seeds_; }

  // Height tiles whose residency changed: their vertices and thicknesses are sampled again.
  void tilesChanged(std::span<const streaming::TileKey> keys);
  void update(const EyeView& view, const PieceSet& pieces, double timeS);
  // The drawn leaves, one mesh per piece (+1 at the end: leaves not yet inside a piece, drawn
  // without imagery), and the seed triangles. `meshes` is resized to pieces.tiles().size() + 1.
  // Most leaves come as references to the drawn chunks (TerrainMesh::chunks): valid until the
  // next update() or output().
  void output(const EyeView& view, const PieceSet& pieces, double timeS, std::vector<TerrainMesh>& meshes,
              std::vector<SeedTriangle>& seeds);

  const RoamFigures& figures() const { return figures_; }
  // Priority (px) a leaf would have for `view`, its constraints ignored (tests).
  double errorPx(const EyeView& view, uint32_t node) const;

 private:
  void finishCompaction();  // before anything changes the mesh: waits for the copy, applies it
  void startCompaction();

  // The owner of the mesh and of the parts that work on it (each owns its own state):
  RoamMesh mesh_;
  geo::LocalFrame frame_;
  RoamOptions options_;
  SeedOptions seeds_;
  int seedLevel_ = 0;
  RoamFigures figures_;
  std::unique_ptr<RoamPriorities> priorities_;  // update, step 1 (roam_priorities.h)
  std::unique_ptr<RoamQueues> queues_;          // update, steps 2 and 3 (roam_queues.h)
  std::unique_ptr<RoamOutput> output_;          // the output traversal and its cache (roam_output.h)
  // Declared after mesh_: destroyed first, it waits for a copy under way (roam_compaction.h).
  std::unique_ptr<RoamCompactor> compactor_;
  static constexpr uint64_t kCompactChurn = 4;
  double compactWaitMs_ = 0.0;
  uint64_t updates_ = 0;
};

}  // namespace vegstream::terrain
