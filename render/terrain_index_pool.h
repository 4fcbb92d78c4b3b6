#pragma once
// The terrain's indices resident on the GPU (issue 44 item 2), beside TerrainGeometryBuffers'
// vertex pool: each chunk's indices, rebased to its range of the vertex pool, are kept in an index
// pool at kIndicesPerVertex × the chunk's first vertex (terrain_chunk_cache.h hands the ranges
// out and keeps them while the chunk's id and version stay the same; an id's triangles never
// change), uploaded with its vertices. Each frame the drawn chunks' indices are gathered from
// there into the frame's index buffer by one compute dispatch (shaders/terrain_index_copy.comp),
// where the frame thread used to rebase every index of every chunk: it now writes only the
// pieces' own indices. The index buffer's bytes are the same.
//
// Contract, per frame: beginFrame(); upload() and gather() for the frame's chunks; then, outside
// rendering and after the staged indices are written, recordUploads(); then, after the frame's
// own indices are copied into its index buffer, recordGather() (which ends with the barrier its
// readers need before they run: the caller's). A range of V vertices holds kIndicesPerVertex · V
// indices: a chunk with more (a planar triangulation has fewer than 2V triangles, so none of
// ROAM's) is not kept here; fits() says so, and the caller writes its indices itself.

#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec4.hpp>

#include "core/task_runner.h"
#include "render/frame_slots.h"
#include "render/growing_buffer.h"
#include "render/handle.h"
#include "terrain/terrain_mesh.h"

namespace vegstream::render {

class TerrainIndexPool {
 public:
  static constexpr int kSlots = kFramesInFlight;
  static constexpr uint32_t kIndicesPerVertex = 6;

  TerrainIndexPool(const Context& ctx, TaskRunner* tasks, VkDeviceSize minimumBytes);

  static bool fits(const terrain::TerrainChunk& c) {
    return c.indices.size() <= size_t{kIndicesPerVertex} * c.vertices.size();
  }
  void beginFrame();
  // `count` of a chunk's indices, staged at `stagedIndex` of the slot's staging index buffer, into
  // its range (the chunk's first vertex `firstVertex`), each plus firstVertex.
  void upload(uint32_t stagedIndex, uint32_t count, uint32_t firstVertex);
  // `count` indices of the chunk at `firstVertex`, from its index `first`, to `targetIndex` of the
  // frame's index buffer.
  void gather(uint32_t firstVertex, uint32_t first, uint32_t count, uint32_t targetIndex);
  // Grows the pool to hold the indices of `vertexCapacity` vertices (a new buffer gets the old
  // one's contents) and records the uploads from `staging` (slot `s`'s staging index buffer).
  void recordUploads(VkCommandBuffer cmd, size_t s, VkBuffer staging, uint64_t vertexCapacity,
                     const GrowingBuffer::Retire& retire);
  // The gather into `indices` (slot `s`'s device index buffer), after the frame's copies into it.
  void recordGather(VkCommandBuffer cmd, size_t s, VkBuffer indices);

  uint64_t gatheredIndices() const { return gatheredIndices_; }  // this frame's
  uint64_t gpuBytes() const;

 private:
  void dispatch(VkCommandBuffer cmd, VkDescriptorSet set, uint32_t first, uint32_t count);
  // Writes the set's bindings 0–2 whose buffer is not the one `bound` says it holds.
  void bindOnce(VkDescriptorSet set, std::array<VkBuffer, 3>& bound, std::array<VkBuffer, 3> buffers);

  const Context* ctx_;
  GrowingBuffer pool_;
  uint64_t poolValid_ = 0;                   // indices written by earlier frames (the pool's used part)
  std::array<GrowingBuffer, kSlots> table_;  // host-visible: this frame's uploads, then its gathers
  std::vector<glm::uvec4> uploads_, gathers_;
  uint64_t gatheredIndices_ = 0;
  DescriptorSetLayout layout_;
  DescriptorPool descriptorPool_;
  std::array<VkDescriptorSet, kSlots> uploadSets_{}, gatherSets_{};
  std::array<std::array<VkBuffer, 3>, kSlots> uploadBound_{}, gatherBound_{};  // what each set holds
  PipelineLayout pipelineLayout_;
  Pipeline pipeline_;
};

}  // namespace vegstream::render
