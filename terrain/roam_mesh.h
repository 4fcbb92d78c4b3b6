#pragma once
// The ROAM triangle bintree itself (Duchaineau et al. 1997; seed 001_3eca9f2c7752e4fb.txt §3.1,
// fig. 4): a forest of bintrees over the root tiles (bintree.h), with the neighbour links that
// make forced splits keep the mesh conforming — no cracks and no T-junctions, across tile
// borders too, because the whole forest is one mesh whose shared edges share their vertices.
//
//   split(t)  splits a leaf and its base neighbour together (a diamond), first splitting the base
//             neighbour's ancestors as far as needed (forced splits);
//   merge(t)  undoes the split of a diamond whose four children are leaves.
//
// Heights: every vertex is sampled once from the finest resident tile when it is created
// (ResidentHeights), and again when the tiles under it change (resample). It starts at the
// height the mesh had there before (the midpoint of its parent's base, or its old height) and
// morphs to the sampled one over `fadeS` (geomorphing, so splits and arriving tiles do not pop).
// Every node keeps its wedgie thickness: the bound of the tile it lies in (wedgie_table.h) plus
// the earth-curvature sagitta of its hypotenuse (a flat triangle in the ENU frame is below the
// curved ground between its vertices), raised where needed so that it nests over the live mesh
// (e_T ≥ |h(m) − (h(l) + h(r)) / 2| + max(e_c0, e_c1), with the vertices' own heights): the
// tables of different tiles and zooms need not nest with each other, the live tree always does.
//
// Pools with free lists: node and vertex indices stay valid until the node or vertex is removed;
// children are allocated in pairs (child1 = child0 + 1). Frame thread only.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "core/task_runner.h"
#include "geo/local_frame.h"
#include "geo/xyz_tiles.h"
#include "terrain/bintree.h"
#include "terrain/resident_heights.h"

namespace vegstream::terrain {

inline constexpr uint32_t kNoNode = std::numeric_limits<uint32_t>::max();

// The height a vertex is drawn at, time t: from `from` to `to` (or its sampled height) over
// fadeS, eased; nodata (a NaN height) stays NaN. RoamVertex::drawnHeight, and the drawn chunks'
// copies of their morphing vertices (roam_tessellator.h).
double morphedHeight(double heightM, double fromHeightM, double toHeightM, double morphStartS, double t, double fadeS);

struct RoamVertex {
  GridPoint grid;
  glm::dvec3 base{0.0};                                           // ENU of the point on the ellipsoid (height 0)
  glm::dvec3 up{0.0, 0.0, 1.0};                                   // the ellipsoid normal there, in the ENU frame
  double heightM = std::numeric_limits<double>::quiet_NaN();      // sampled (target) height; NaN: nodata
  double fromHeightM = std::numeric_limits<double>::quiet_NaN();  // what it morphs from
  double toHeightM = std::numeric_limits<double>::quiet_NaN();  // what it morphs to: heightM, or its base while merging
  double morphStartS = -1e30;
  bool merging = false;  // sinking to the midpoint of its diamond's base before the merge
  glm::vec3 normal{0.0f, 0.0f, 1.0f};
  int sourceZoom = -1;
  glm::dvec3 at{0.0};  // position(geometryHeight(fill)): what culling and priorities use

  // Height used for culling and priorities: nodata counts as the fill height (never drawn).
  double geometryHeight(double fill) const { return heightM == heightM ? heightM : fill; }
  glm::dvec3 position(double h) const { return base + up * h; }
  // The height drawn at time t: from fromHeightM to toHeightM over fadeS.
  double drawnHeight(double t, double fadeS) const;
  bool morphDone(double t, double fadeS) const { return t - morphStartS >= fadeS; }
};

// Laid out for the priority traversal, which visits tens of thousands of nodes a frame, most of
// them cache misses: what it reads fills the first 64 bytes (a cache line: the node is aligned
// to one), the links and the output's fields the second. A visit then reads one line of the
// node and one of each child, not two or three of each.
struct alignas(64) RoamNode {
  // --- The priority traversal's line.
  TriPath path;
  uint32_t child = kNoNode;  // the first of the pair
  uint32_t mid = kNoNode;    // the split vertex, while split
  float thickness = 0.0f;    // nested wedgie thickness + sagitta (m); NaN: unknown; < 0: no data
  float priority = 0.0f;     // the last priority the update gave it
  float radius = 0.0f;       // bounding sphere about the base midpoint (m, at geometry heights)
  uint8_t seenCull = 0xFF, seenPiece = 0xFF;  // the cull and piece states the priority was computed under
  // Deferred priority recomputation (the tessellator's, roam_tessellator.h): `priority` stays on
  // the same side of the split / merge bounds until the camera has travelled `deadline` metres
  // on the tessellator's odometer; subtreeDeadline is the least over the subtree. −∞: evaluate
  // again (new, changed, or next to a bound); the mesh expires what it changes.
  double deadline = -std::numeric_limits<double>::infinity();
  double subtreeDeadline = -std::numeric_limits<double>::infinity();
  // --- The links, and the output's fields.
  uint32_t v[3] = {0, 0, 0};                                 // apex, left, right (RoamVertex indices)
  uint32_t parent = kNoNode;
  uint32_t base = kNoNode, left = kNoNode, right = kNoNode;  // neighbours across base, apex–left, apex–right
  uint32_t leafCount = 1;         // leaves in the subtree (what a drawn chunk here would hold)
  uint32_t drawnChunk = kNoNode;  // the cache slot attached to a chunk root (released when freed)
  // Drawn chunks (the tessellator's output cache) span a node's whole subtree. drawnStamp: the
  // mesh's drawn epoch when this node, or one below it, last changed in a way that shows.
  uint64_t drawnStamp = 0;
  bool isLeaf() const { return child == kNoNode; }
  // The thickness culling uses: unknown (NaN) or no data (< 0) count as flat.
  float cullThickness() const { return std::max(0.0f, thickness == thickness ? thickness : 0.0f); }
};
static_assert(offsetof(RoamNode, subtreeDeadline) + sizeof(double) == 64, "the traversal's fields fill one line");
static_assert(sizeof(RoamNode) == 128);

struct RoamMeshOptions {
  double fadeS = 0.5;        // geomorph time (s)
  double fillHeightM = 0.0;  // the height nodata vertices count as for culling (e.g. mid dataset)
};

// compact()'s renumbering: new index of every old node and vertex (kNoNode: free).
struct RoamRenumbering {
  std::vector<uint32_t> nodes, vertices;
};

// A compaction in three steps, so that its copy (milliseconds: every node and vertex, read in
// tree order) can run on another thread while the frame goes on (roam_tessellator.h).
struct RoamCompaction {
  std::vector<RoamNode> nodes;
  std::vector<RoamVertex> vertices;
  RoamRenumbering renumbering;
  // Scratch (roam_mesh_compaction.cpp): every split node's rank in preorder, by node; and by
  // rank, its split vertex and base neighbour.
  struct Split {
    uint32_t mid, base;
  };
  std::vector<uint32_t> ranks;
  std::vector<Split> splits;
};

class RoamMesh {
 public:
  // One root tile pair for every tile of `roots` (at grid.rootZoom()).
  RoamMesh(BintreeGrid grid, geo::TileRange roots, const geo::LocalFrame& frame, ResidentHeights& heights,
           RoamMeshOptions options = {});

  const BintreeGrid& grid() const { return grid_; }
  const RoamMeshOptions& options() const { return options_; }
  void setTime(double timeS) { timeS_ = timeS; }
  // The mesh has been drawn (the output calls it): from then on new and resampled vertices
  // morph. Before the first drawn frame there is nothing on screen to morph from; a morph then
  // drew the first frames' surface at the coarse interpolation it starts from — 39 m under the
  // Kolob plateau 2 m below a camera — while culling used the true heights, which cut holes in
  // the view (and warm-up frames, all at the start time, never finished it).
  void markShown() { shown_ = true; }
  bool shown() const { return shown_; }

  // Splits leaf t (and its diamond partner, forcing splits of coarser neighbours first). False
  // when t or a node it would force is at the deepest level. Invalidates references to nodes.
  // `created` (optional) receives every node made a leaf by the split, forced ones included.
  bool split(uint32_t t, std::vector<uint32_t>* created = nullptr);
  // T and its base neighbour (if any) are split, their children leaves, and they form a diamond.
  bool isMergeable(uint32_t t) const;
  void merge(uint32_t t);
  // Merge morphs (so merges do not pop either): the split vertex of mergeable diamond t starts
  // sinking to its base's midpoint; or, when the diamond is no longer to merge, rises back.
  void beginMergeMorph(uint32_t t);
  void cancelMergeMorph(uint32_t t);

  // Marks t's priority as to be computed again, and every ancestor's subtree as holding one.
  void expire(uint32_t t);
  // Marks t as changed on screen, and its ancestors (a drawn chunk may start at any of them).
  void markDrawnChanged(uint32_t t);
  // The drawn epoch: every change marked from now on gets a later stamp than what this
  // returns (the output calls it once before it builds chunks).
  uint64_t closeDrawnEpoch() { return drawnEpoch_++; }
  // The drawnChunk slots of nodes freed since the last call.
  std::vector<uint32_t> takeReleasedChunks() { return std::exchange(releasedChunks_, {}); }

  // Renumbers nodes and vertices in depth-first order (roots and root corners keep theirs), so
  // traversals walk memory forwards: splits and merges scatter the pools over time. Every node
  // and vertex index held outside is invalid afterwards, and every node's drawnChunk is
  // kNoNode: drawn chunks are the tessellator's, and it attaches them again.
  RoamRenumbering compact() {
    RoamCompaction c = beginCompaction();
    buildCompaction(c);
    return endCompaction(std::move(c));
  }
  // compact() in steps. begin and end on the thread that owns the mesh; build on any thread,
  // while nothing changes the mesh in between (it only reads it), with its subtrees copied in
  // parallel on `tasks` when given (the same result with any number of threads).
  RoamCompaction beginCompaction();  // hands the spare pools out
  void buildCompaction(RoamCompaction& c, TaskRunner* tasks = nullptr) const;
  RoamRenumbering endCompaction(RoamCompaction&& c);  // the copy becomes the mesh
  // Node pairs allocated since the last compaction (or construction), against those live: how
  // far the pools have drifted from depth-first order.
  uint64_t pairsAllocatedSinceCompact() const { return pairsAllocated_; }
  uint64_t livePairs() const { return nodes_.size() / 2 - freePairs_.size(); }
  // Room for a mesh of `leaves` leaves without reallocating the pools: growing them in a frame
  // copies every node and faults the new pages in (milliseconds). Every page of the pools (and of
  // the compaction's spares) is touched here, not by the splits that first use it.
  void reserve(uint64_t leaves);

  // Samples the vertices and thicknesses inside `tile`'s square again (its residency changed).
  void resample(const geo::TileId& tile);

  // The traversals are bound by fetching nodes and vertices: a node being visited asks for its
  // children and split vertex early, so they are in cache by the time the visit needs them. The
  // priority traversal reads the children's first lines only (RoamNode).
  void prefetchChildren(uint32_t t) const {
    const RoamNode& n = nodes_[t];
    if (n.isLeaf()) return;
    const char* c = reinterpret_cast<const char*>(&nodes_[n.child]);
    for (size_t at = 0; at < 2 * sizeof(RoamNode); at += 64) __builtin_prefetch(c + at);
    __builtin_prefetch(&vertices_[n.mid].at);
  }
  void prefetchChildrenForPriorities(uint32_t t) const {
    const RoamNode& n = nodes_[t];
    if (n.isLeaf()) return;
    __builtin_prefetch(&nodes_[n.child]);
    __builtin_prefetch(&nodes_[n.child + 1]);
    __builtin_prefetch(&vertices_[n.mid].at);
  }
  void prefetchVertex(uint32_t v) const {
    const char* x = reinterpret_cast<const char*>(&vertices_[v]);
    for (size_t at = 0; at < sizeof(RoamVertex); at += 64) __builtin_prefetch(x + at);
  }
  const RoamNode& node(uint32_t i) const { return nodes_[i]; }
  RoamNode& node(uint32_t i) { return nodes_[i]; }
  const RoamVertex& vertex(uint32_t i) const { return vertices_[i]; }
  const std::vector<uint32_t>& roots() const { return roots_; }
  size_t nodeCapacity() const { return nodes_.size(); }
  size_t vertexCapacity() const { return vertices_.size(); }
  uint64_t leafCount() const { return leaves_; }
  uint64_t vertexCount() const { return vertices_.size() - freeVertices_.size(); }
  TriCorners corners(uint32_t t) const {
    const RoamNode& n = nodes_[t];
    return {vertices_[n.v[0]].grid, vertices_[n.v[1]].grid, vertices_[n.v[2]].grid};
  }

  // Every leaf, depth first from the roots (tests, benchmarks).
  std::vector<uint32_t> leaves() const;
  // Checks the links and the conformity of the mesh: every leaf edge is either on the boundary of
  // the forest or shared with exactly one leaf with the same two vertices. Returns the number of
  // violations (0 for a valid mesh).
  uint64_t conformityViolations() const;

 private:
  uint32_t allocPair();
  void freePair(uint32_t first);
  uint32_t newVertex(GridPoint p, double fromHeight);
  void sampleVertex(RoamVertex& v, bool morph);
  void applySample(RoamVertex& v, const HeightSample& s, bool morph);
  void splitOne(uint32_t t, uint32_t mid, std::vector<uint32_t>* created);
  void mergeOne(uint32_t t);
  void replaceLink(uint32_t at, uint32_t from, uint32_t to);
  float thicknessOf(uint32_t t);
  float nestedThickness(uint32_t t) const;
  void updateRadius(uint32_t t);
  void raiseThickness(uint32_t t);
  void markDiamondLeaves(uint32_t t);
  void addLeaves(uint32_t t, int delta);  // to t's and its ancestors' leafCount
  void resampleNode(uint32_t t, const geo::TileId& tile, uint32_t lo[2], uint32_t hi[2]);

  BintreeGrid grid_;
  geo::LocalFrame frame_;
  ResidentHeights* heights_;
  RoamMeshOptions options_;
  double timeS_ = 0.0;
  bool shown_ = false;  // markShown
  std::vector<RoamNode> nodes_;
  std::vector<uint32_t> freePairs_;
  std::vector<RoamVertex> vertices_;
  std::vector<uint32_t> freeVertices_;
  std::vector<uint32_t> roots_;
  std::vector<uint32_t> cornerVertices_;  // the root tiles' corners (never removed)
  uint64_t leaves_ = 0;
  std::vector<uint32_t> releasedChunks_;
  std::vector<RoamNode> spareNodes_;  // compact()'s scratch, kept so that it does not fault pages in again
  std::vector<RoamVertex> spareVertices_;
  uint64_t drawnEpoch_ = 1;
  uint64_t pairsAllocated_ = 0;
};

}  // namespace vegstream::terrain
