#pragma once
// A drawn leaf → its vertices and triangle (internal to the tessellator's output: the direct
// output, roam_output.h, and the drawn chunks, roam_chunks.h). What a sink holds is what the
// renderer draws: positions relative to the sink's origin at the height drawn now (morphs
// included), uvs in the sink's piece; a vertex already in the sink is not emitted again — the
// direct output knows which by per-output stamps, a chunk being built by its own map (so that
// chunks are built on any thread).

#include <bit>
#include <cassert>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "geo/xyz_tiles.h"
#include "terrain/roam_mesh.h"
#include "terrain/terrain_mesh.h"

namespace vegstream::terrain {

// RoamVertex → index in the chunk being built, by open addressing. A chunk of L leaves has at
// most 3L vertices and the table 4 × (3L + 3) slots or more, so it stays under a quarter full
// and probes stay short.
class ChunkVertexMap {
 public:
  explicit ChunkVertexMap(uint32_t maxLeaves)
      : mask_(std::bit_ceil(4u * (3u * maxLeaves + 3u)) - 1u), bits_(std::countr_zero(mask_ + 1u)),
        keys_(mask_ + 1u, kNoNode), values_(mask_ + 1u, kNoNode) {}
  // v's index in the chunk; kNoNode (to be set by the caller) when v is not in it yet.
  uint32_t& at(uint32_t v) {
    assert(v != kNoNode);
    for (uint32_t i = (v * 2654435761u) >> (32 - bits_);; i = (i + 1) & mask_) {
      if (keys_[i] == v) return values_[i];
      if (keys_[i] == kNoNode) {
        assert(used_.size() * 2 < mask_);
        keys_[i] = v;
        used_.push_back(i);
        return values_[i];
      }
    }
  }
  void clear() {
    for (uint32_t i : used_) keys_[i] = values_[i] = kNoNode;
    used_.clear();
  }

 private:
  uint32_t mask_;
  int bits_;
  std::vector<uint32_t> keys_, values_, used_;
};

// A drawn chunk's vertex still morphing (roam_chunks.h), with a copy of what moving it needs (to
// move it each output without a cache miss in the vertex pool: a change of the copied morph
// changes the chunk — RoamMesh stamps every leaf of a vertex whose morph it starts, cancels or
// resamples; 88 bytes, not the 144 of a RoamVertex: most chunks moved are read only for it).
struct MorphingVertex {
  uint32_t at;          // index in the chunk's vertices
  glm::dvec3 base, up;  // RoamVertex's: the same arithmetic as emitting it
  double heightM, fromHeightM, toHeightM, morphStartS;
  explicit MorphingVertex(uint32_t index, const RoamVertex& v)
      : at(index), base(v.base), up(v.up), heightM(v.heightM), fromHeightM(v.fromHeightM), toHeightM(v.toHeightM),
        morphStartS(v.morphStartS) {}
  double drawnHeight(double t, double fadeS) const {
    return morphedHeight(heightM, fromHeightM, toHeightM, morphStartS, t, fadeS);
  }
  glm::dvec3 position(double h) const { return base + up * h; }
  bool morphDone(double t, double fadeS) const { return t - morphStartS >= fadeS; }
};

// The direct output's per-output vertex stamps: which mesh a RoamVertex went into last, and where.
struct VertexStamp {
  uint64_t frame = 0;
  uint32_t piece = 0, index = 0;
};

struct EmitCounts {
  uint64_t leaves = 0, morphingVertices = 0, chunksMoved = 0;
  void add(const EmitCounts& o) {
    leaves += o.leaves;
    morphingVertices += o.morphingVertices;
    chunksMoved += o.chunksMoved;
  }
};

// Where emitLeaf writes: a piece's mesh (stamps), or a drawn chunk being built (chunkVertices,
// and what the chunk keeps beside its mesh: morphing).
struct LeafSink {
  std::vector<TerrainVertex>* vertices;
  std::vector<uint32_t>* indices;
  glm::dvec3 origin;
  const geo::TileId* tile;           // the piece (uv), or null: untextured
  std::vector<VertexStamp>* stamps;  // a piece's mesh: which vertices are already in it
  uint64_t frame;                    // the output those stamps are of
  uint32_t stamp;                    // the piece those stamps are of
  ChunkVertexMap* chunkVertices;     // a chunk: which vertices are already in it (instead of stamps)
  EmitCounts* counts;
  std::vector<MorphingVertex>* morphing;  // a chunk: its vertices still morphing
};

// Leaf `t` at time `timeS` into `sink`; false: nodata (a hole, never a drop to 0).
bool emitLeaf(const RoamMesh& mesh, double timeS, uint32_t t, const LeafSink& sink);

}  // namespace vegstream::terrain
