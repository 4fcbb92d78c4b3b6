#pragma once
// DrawnChunks (internal to the tessellator: the output cache, roam_tessellator.h output()).
// The topmost node on the output's way down that is inside one piece, beyond the seeds, not
// wholly outside the view and holds at most RoamOptions::chunkMaxLeaves leaves keeps its
// subtree's leaves as drawn (a TerrainChunk handed out by reference, never copied), as long as
// nothing in them changed (RoamNode::drawnStamp); only its morphing vertices are moved (a new
// version). One that straddles the edge of the view is drawn whole: culling its triangles one by
// one cost the output a sixth of its time and saved the GPU about 1 % of the terrain's
// triangles, all outside the view (clipped before they cost a fragment). It owns the chunks (slots attached to their roots, RoamNode::drawnChunk), their ids, the drawn
// epoch of this output, the draws claimed this output and the scratch that builds them.
//
// Contract, per output: beginOutput(); draw() for each chunk root the traversal reaches, in
// traversal order (ids are handed out there, in order); finish(): the claimed chunks built
// again or moved — on RoamOptions::tasks in blocks of chunks, each touching only its
// own — then their draws appended to the pieces' meshes in traversal order, so the output is
// the same with any number of threads. Without tasks draw() does all of it at once, while the
// chunk is in the cache. Between outputs: release() (chunks whose root the mesh freed),
// dropIdle() (unused for kChunkIdleFrames outputs), remap() (after a compaction).
// Counts chunksBuilt, chunksReused and drawnTriangles into the figures.

#include <cstdint>
#include <deque>
#include <vector>

#include <glm/vec3.hpp>

#include "geo/xyz_tiles.h"
#include "terrain/eye_space.h"
#include "terrain/roam_leaves.h"
#include "terrain/roam_mesh.h"
#include "terrain/roam_tessellator.h"
#include "terrain/terrain_mesh.h"

namespace vegstream::terrain {

// What the output reads of every chunk it reaches, every frame, kept apart from the chunk's
// vertices in one dense array (DrawnChunks::state_): a chunk reused as it was is decided and
// appended from here alone. Read in the chunks' own records (160 bytes each, scattered), this
// was three quarters of the time of DrawnChunks::draw, a cache miss per chunk (perf); the draws
// handed out carry the chunk's header from here too (terrain_mesh.h TerrainChunkDraw).
struct ChunkState {
  uint32_t root = kNoNode;
  uint64_t builtStamp = 0;  // the mesh's drawn epoch when built
  uint64_t usedFrame = 0;
  geo::TileId piece{};     // positions are relative to its origin, uvs in it
  bool rebuild = false;    // this output builds it again (draw → finish)
  bool morphing = false;   // some of its vertices still move (DrawnChunk::morphing)
  TerrainChunkDraw drawn;  // its draw, header included, as last built or moved
};

// A chunk's geometry: what the renderer draws, and how to move it.
struct DrawnChunk {
  TerrainChunk mesh;
  // The vertices still morphing, each with a copy of what moving it needs (roam_leaves.h).
  std::vector<MorphingVertex> morphing;
};

// One output's: what its chunks are drawn for.
struct ChunkPass {
  const EyeView* view = nullptr;
  const Frustum* frustum = nullptr;  // the view's planes
  const PieceSet* pieces = nullptr;
  std::vector<TerrainMesh>* meshes = nullptr;  // the pieces' meshes: origins, and where draws go
  double timeS = 0.0;
  EmitCounts* emitted = nullptr;  // the output's counts (draw() without tasks, finish())
  // False while a compaction's copy reads the nodes: a new chunk's slot is attached to its root
  // afterwards (remap() attaches every chunk to its root again).
  bool attach = true;
};

class DrawnChunks {
 public:
  static constexpr uint64_t kChunkIdleFrames = 64;

  // Every reference outlives this.
  DrawnChunks(RoamMesh& mesh, const RoamOptions& options, RoamFigures& figures);

  // Releases the chunks whose root was freed; changes of the mesh from here on are after every
  // chunk this output builds.
  void beginOutput();
  // The chunk of root `t` (not wholly outside the view) in piece `piece`.
  void draw(const ChunkPass& pass, uint32_t t, int piece);
  void finish(const ChunkPass& pass);

  void release();
  void dropIdle();
  void remap(const RoamRenumbering& renumbering);

 private:
  struct ChunkDraw {
    uint32_t slot;
    int piece;
  };
  // A block's vertex map and leaf list, kept from output to output.
  struct ChunkScratch {
    ChunkVertexMap map;
    std::vector<uint32_t> leaves;  // collect's
  };
  uint32_t slotFor(uint32_t t, bool attach);
  void freeSlot(uint32_t slot);  // its chunk and state emptied, the slot free for another
  void prepareAll(const ChunkPass& pass);
  // Any thread: reads the mesh, writes this chunk and its state (and the caller's scratch and
  // counts) only.
  void prepare(const ChunkPass& pass, size_t draw, ChunkScratch& scratch, EmitCounts& counts);
  void rebuild(const ChunkPass& pass, uint32_t slot, const glm::dvec3& origin, ChunkScratch& scratch,
               EmitCounts& counts);
  void move(const ChunkPass& pass, DrawnChunk& chunk, const glm::dvec3& origin, EmitCounts& counts);
  void append(const ChunkPass& pass, const ChunkDraw& d);
  // A chunk's leaves, depth first, into `leaves` (their vertices asked for ahead of emitLeaf).
  void collect(uint32_t root, std::vector<uint32_t>& leaves) const;

  RoamMesh& mesh_;
  const RoamOptions& options_;
  RoamFigures& figures_;
  std::deque<DrawnChunk> chunks_;  // a deque: the TerrainChunks handed out keep their address
  std::vector<ChunkState> state_;  // by slot, as chunks_
  std::vector<uint32_t> freeChunks_;
  uint64_t nextChunkId_ = 1;
  uint64_t chunkEpoch_ = 0;  // this output's (RoamMesh::closeDrawnEpoch)
  uint64_t outputFrame_ = 0;
  std::vector<ChunkDraw> draws_;            // this output's, in traversal order
  std::vector<ChunkScratch> chunkScratch_;  // kept from output to output
};

}  // namespace vegstream::terrain
