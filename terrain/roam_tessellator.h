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

struct ErrorGeometry;  // roam_error.h

// Priority of a leaf that must split whatever its error (a constraint).
inline constexpr float kForcedPriority = 3.0e38f;

struct RoamOptions {
  double maxErrorPx = 2.0;          // screen-space error bound
  uint64_t maxTriangles = 120000;   // leaves in the mesh (the constraints may exceed it)
  double mergeFraction = 0.6;       // merge diamonds whose priority is below this × the bound
  uint64_t maxOpsPerFrame = 60000;  // splits + merges per frame (a deterministic work budget)
  double maxQueueMs = 0.0;          // a time budget for the queue work; 0: none (deterministic)
  double canopyM = 30.0;            // the tallest plant: wedgies grow by it for culling
  bool cacheChunks = true;          // output: append unchanged drawn chunks as cached (roam_output.cpp)
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
  enum class InPiece : uint8_t { None, Above, In };
  struct Candidate {
    float priority;
    uint32_t node;
    TriPath path;
  };
  struct Walk;  // the state of one traversal

  // geometry (optional) receives the error geometry when the priority came from it.
  float priority(const EyeView& view, uint32_t t, const glm::dvec3* eye, Cull cull, InPiece ps,
                 ErrorGeometry* geometry = nullptr) const;
  double sphereDistance(const EyeView& view, uint32_t t, const glm::dvec3* eye, double thickness) const;
  double projectedErrorPx(const EyeView& view, uint32_t t, const glm::dvec3* eye, double thickness) const;
  InPiece pieceState(const PieceSet& pieces, const geo::TileId& square, InPiece parent, int level) const;
  InPiece pieceStateOf(const PieceSet& pieces, uint32_t t) const;
  // Inline: the traversals call them for every node they descend through.
  void eyeOf(const EyeView& view, uint32_t t, glm::dvec3* eye) const {
    const RoamNode& n = mesh_.node(t);
    for (int i = 0; i < 3; ++i) eye[i] = eyeOfVertex(view, n.v[i]);
  }
  glm::dvec3 eyeOfVertex(const EyeView& view, uint32_t v) const { return view.toEye(mesh_.vertex(v).at); }
  // The priority traversal (roam_priorities.cpp). With options_.tasks, the frame thread walks
  // the top of the tree and hands each subtree of at most kTaskLeaves leaves to a task; the
  // tasks' results are put back together in the order one traversal gives.
  struct PriorityFigures {
    uint64_t visited = 0, computed = 0;
    double achievedErrorPx = 0.0;
    void add(const PriorityFigures& o);
  };
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
  void computePriorities(Walk& w);
  // `planes`: those the parent's wedgie straddles, when `cull` is Partial (eye_space.h).
  void descendPriorities(Walk& w, uint32_t t, const glm::dvec3* eye, Cull cull, PlaneMask planes, InPiece ps);
  void visitPriorities(Walk& w, uint32_t t, const glm::dvec3* eye, Cull cull, PlaneMask planes, InPiece ps);
  void visitOutput(Walk& w, uint32_t t, const glm::dvec3* eye, Cull cull, PlaneMask planes, InPiece ps, int piece,
                   bool seeds);
  // Which vertices a chunk being built holds already (roam_chunks.cpp): a small map of its own,
  // so that chunks are built on any thread (the direct output uses stamps_).
  class ChunkVertexMap;
  struct DrawnChunk;  // below: the output cache
  struct EmitCounts {
    uint64_t leaves = 0, morphingVertices = 0, chunksMoved = 0;
    void add(const EmitCounts& o) {
      leaves += o.leaves;
      morphingVertices += o.morphingVertices;
      chunksMoved += o.chunksMoved;
    }
  };
  // Where emitLeaf writes: a piece's mesh, or a drawn chunk being built.
  struct LeafSink {
    std::vector<TerrainVertex>* vertices;
    std::vector<uint32_t>* indices;
    glm::dvec3 origin;
    const geo::TileId* tile;          // the piece (uv), or null: untextured
    uint32_t stamp;                   // a piece's mesh: which vertices are already in it (stamps_)
    ChunkVertexMap* chunkVertices;    // a chunk: which vertices are already in it (instead of stamps_)
    EmitCounts* counts;
    DrawnChunk* chunk;                // a chunk: also its morphing vertices, thickness and at
  };
  bool emitLeaf(double timeS, uint32_t t, const LeafSink& sink);  // false: nodata (a hole)
  // The output's chunks (roam_chunks.cpp), in three steps so that the work per chunk runs on
  // options_.tasks: the traversal claims each chunk it reaches and queues it (drawChunk); then
  // every queued chunk is built again, or has its morphing vertices moved, and, where it
  // straddles the edge of the view (partial), has its triangles culled one by one
  // (prepareChunks, in parallel: each touches its own chunk); then the draws are appended to
  // the pieces' meshes in traversal order (appendChunkDraws). Without tasks drawChunk does all
  // three at once, while the chunk is in the cache.
  struct ChunkDraw {
    uint32_t slot;
    int piece;
    PlaneMask planes;  // the planes of the view its root's wedgie straddles (none: wholly inside)
  };
  struct ChunkScratch;  // roam_walk.h: a block's vertex map, plane distances and leaf list
  void drawChunk(Walk& w, uint32_t t, int piece, PlaneMask planes);
  void prepareChunks(Walk& w);
  void prepareChunk(const Walk& w, size_t draw, ChunkScratch& scratch, EmitCounts& counts);
  void appendChunkDraws(Walk& w);
  void appendChunkDraw(Walk& w, const ChunkDraw& d);
  std::vector<ChunkScratch> chunkScratch_;  // kept from output to output
  // A chunk's leaves, depth first, into `leaves` (their vertices asked for ahead of emitLeaf).
  void collectChunk(uint32_t root, std::vector<uint32_t>& leaves) const;
  void releaseChunks();
  void dropIdleChunks();
  static constexpr uint64_t kChunkIdleFrames = 64;
  void remapChunks(const RoamRenumbering& renumbering);
  void emitSeed(Walk& w, const TriPath& path, const glm::dvec3* world, const glm::dvec3* eye, bool interpolated,
                int piece);
  void refineSeeds(Walk& w, const TriPath& path, const glm::dvec3* world, const glm::dvec3* eye, double thickness,
                   int piece);
  // `w`: the update's walk (its view, frustum and pieces).
  void splitPhase(const Walk& w, std::vector<Candidate>& candidates, uint64_t& ops, const Stopwatch& watch);
  void mergePhase(std::vector<Candidate>& diamonds, uint64_t& ops, const Stopwatch& watch);
  bool outOfWork(uint64_t ops, const Stopwatch& watch);
  void lowerDeadline(uint32_t t, double deadline);  // and its ancestors' subtree deadlines

  RoamMesh mesh_;
  geo::LocalFrame frame_;
  RoamOptions options_;
  SeedOptions seeds_;
  int seedLevel_ = 0;
  double fillHeightM_ = 0.0;
  RoamFigures figures_;
  // Deferred priority recomputation (Duchaineau et al. 1997 §6): the camera's odometer (metres
  // travelled), and what a change of which means every priority is computed again.
  void beginUpdate(const EyeView& view);
  void evaluateLeaf(const EyeView& view, uint32_t t, const glm::dvec3* eye, Cull cull, InPiece ps,
                    PriorityFigures& counts);
  void evaluateDiamond(Walk& w, uint32_t t, const glm::dvec3* eye, Cull cull, InPiece ps);
  std::vector<PriorityTask> priorityTasks_;  // reused: their vectors keep their capacity
  double odometerM_ = 0.0;
  glm::dvec3 lastCamera_{std::numeric_limits<double>::quiet_NaN()};
  glm::dvec3 lastUp_{0.0};
  struct Projection {
    double nearM = 0.0, pixelsPerRadian = 0.0, tanHalfX = 0.0, tanHalfY = 0.0, boundPx = 0.0, mergePx = 0.0;
    auto operator<=>(const Projection&) const = default;
  } lastProjection_;
  bool evaluateAll_ = true;  // this update computes every priority again
  // The output cache (roam_output.cpp): the topmost node on the way down that is inside one
  // piece, beyond the seeds, not wholly outside the view and holds at most chunkMaxLeaves
  // leaves keeps its subtree's leaves as drawn (a TerrainChunk handed out by reference, never
  // copied), as long as nothing in them changed (RoamNode::drawnStamp); only its morphing
  // vertices are moved (a new version); where it straddles the edge of the view, its triangles
  // are culled one by one. Chunks unused for kChunkIdleFrames outputs are dropped.
  struct DrawnChunk {
    uint32_t root = kNoNode;
    uint64_t builtStamp = 0;  // the mesh's drawn epoch when built
    uint64_t usedFrame = 0;
    geo::TileId piece{};  // positions are relative to its origin, uvs in it
    TerrainChunk mesh;
    // The vertices still morphing, each with a copy of what moving it needs (to move it each
    // output without a cache miss in the vertex pool: a change of the copied morph changes the
    // chunk — RoamMesh stamps every leaf of a vertex whose morph it starts, cancels or
    // resamples; 88 bytes, not the 144 of a RoamVertex: most chunks moved are read only for it), and
    // each triangle's wedgie thickness: where the chunk straddles the edge of the view its
    // triangles are culled one by one (a leaf's wedgie nests in its ancestors', so that gives
    // what the hierarchical culling does).
    struct Morphing {
      uint32_t at;  // index in mesh.vertices
      glm::dvec3 base, up;  // RoamVertex's: the same arithmetic as emitting it
      double heightM, fromHeightM, toHeightM, morphStartS;
      explicit Morphing(uint32_t index, const RoamVertex& v)
          : at(index), base(v.base), up(v.up), heightM(v.heightM), fromHeightM(v.fromHeightM), toHeightM(v.toHeightM),
            morphStartS(v.morphStartS) {}
      double drawnHeight(double t, double fadeS) const {
        return morphedHeight(heightM, fromHeightM, toHeightM, morphStartS, t, fadeS);
      }
      glm::dvec3 position(double h) const { return base + up * h; }
      bool morphDone(double t, double fadeS) const { return t - morphStartS >= fadeS; }
    };
    std::vector<Morphing> morphing;
    std::vector<float> thickness;
    // Each vertex's RoamVertex::at (what culling uses), kept here: reading it from the vertex
    // pool was a cache miss per vertex. A change of it changes the chunk (RoamMesh::resample).
    std::vector<glm::dvec3> at;
    bool rebuild = false;           // this output builds it again (drawChunk → prepareChunks)
    std::vector<uint32_t> visible;  // partly in view: the triangles drawn this output (prepareChunk)
  };
  std::deque<DrawnChunk> chunks_;            // a deque: the TerrainChunks handed out keep their address
  uint64_t nextChunkId_ = 1;
  uint64_t chunkEpoch_ = 0;  // this output's (RoamMesh::closeDrawnEpoch)
  std::vector<uint32_t> freeChunks_;
  // Per-output vertex stamps: which mesh a RoamVertex went into last, and where.
  struct Stamp {
    uint64_t frame = 0;
    uint32_t piece = 0, index = 0;
  };
  std::vector<Stamp> stamps_;
  uint64_t outputFrame_ = 0;
  static constexpr uint64_t kCompactChurn = 4;
  // A compaction whose copy runs on options_.tasks (RoamOptions::tasks): whoever claims it first,
  // the worker or finishCompaction(), makes the copy.
  struct PendingCompaction;
  std::shared_ptr<PendingCompaction> compaction_;
  void startCompaction();
  void finishCompaction();  // before anything changes the mesh: waits for the copy, applies it
  double compactWaitMs_ = 0.0;
  uint64_t updates_ = 0;
  double timeS_ = 0.0;
};

}  // namespace vegstream::terrain
