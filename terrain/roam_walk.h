#pragma once
// Internal to roam_tessellator*.cpp: the state one traversal of the bintree carries.

#include <bit>
#include <cassert>
#include <cstdint>
#include <limits>
#include <vector>

#include "terrain/roam_tessellator.h"

namespace vegstream::terrain {

// Deadlines (RoamNode::deadline): never due until the cull, piece or mesh changes; due now.
inline constexpr double kNever = std::numeric_limits<double>::infinity();
inline constexpr double kNow = -std::numeric_limits<double>::infinity();

// RoamVertex → index in the chunk being built, by open addressing. A chunk of L leaves has at
// most 3L vertices and the table 4 × (3L + 3) slots or more, so it stays under a quarter full
// and probes stay short.
class RoamTessellator::ChunkVertexMap {
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

struct RoamTessellator::ChunkScratch {
  ChunkVertexMap map;
  std::vector<PlaneDistances> planes;  // each vertex's, by plane
  std::vector<uint32_t> leaves;  // collectChunk's
};

struct RoamTessellator::Walk {
  const EyeView* view = nullptr;
  const Frustum* frustum = nullptr;  // the view's planes
  const PieceSet* pieces = nullptr;
  double bound = 0.0;
  double timeS = 0.0;
  // update()
  std::vector<Candidate>* splits = nullptr;
  std::vector<Candidate>* diamonds = nullptr;
  double mergeBelow = 0.0;
  bool overBudget = false;
  PriorityFigures counts;
  std::vector<uint32_t>* cancels = nullptr;  // diamonds whose merge morph is cancelled after the traversal
  // The top of a parallel traversal (computePriorities): the subtrees handed to tasks, and the
  // nodes above them, post-order, whose subtree deadlines wait for the tasks.
  std::vector<PriorityTask>* tasks = nullptr;
  size_t taskCount = 0;
  std::vector<uint32_t> waiting;
  // output()
  std::vector<TerrainMesh>* meshes = nullptr;
  std::vector<SeedTriangle>* seeds = nullptr;
  int untextured = -1;  // index of the mesh for leaves not yet inside a piece
  std::vector<ChunkDraw> chunkDraws;  // in traversal order (drawChunk)
  EmitCounts emitted;                 // the direct output's
};

}  // namespace vegstream::terrain
