#pragma once
// The terrain's geometry on the GPU, for TerrainPass and the passes that read it (the deferred
// shade, the compute raster): each frame, one index buffer holding every drawn piece's triangles
// in draw order (so a triangle's index in it is its id), and the vertices they index.
//
// Two ways to keep the vertices (TerrainGeometry in renderer.h chooses; the images are the same
// byte for byte, tests/render/terrain_residency_test.cpp):
// - resident (the default): one device-local vertex pool for all frame slots, in which each
//   TerrainChunk keeps its range while its id and version stay the same
//   (terrain_chunk_cache.h); a frame copies only new and moved chunks and the meshes' own
//   vertices, and its indices point into the pool (a piece's vertex offset is 0); the chunks'
//   indices are resident too (terrain_index_pool.h), and those of a chunk drawn in full are
//   gathered into the frame's index buffer on the GPU;
// - copied: every frame flattens every piece (own vertices, then each chunk's) into the frame
//   slot's buffers, a piece's indices relative to its vertex offset — the way before residency.
// Either way the bytes go through the slot's host-visible staging buffers into device-local
// memory: when copied, one copy command each; when resident, the vertex uploads by one compute
// dispatch (shaders/terrain_upload.comp: a copy region per chunk cost 2.4 µs of GPU time each on
// the H100) and the indices by a copy command; the per-piece work runs on the TaskRunner and the calling
// thread, each piece writing only its own ranges, so the bytes do not depend on the threads.

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "core/task_runner.h"
#include "render/frame_slots.h"
#include "render/frame_types.h"
#include "render/growing_buffer.h"
#include "render/handle.h"
#include "render/terrain_chunk_cache.h"
#include "render/terrain_index_pool.h"

namespace vegstream::render {

// Where a drawn piece's triangles are in the frame's index buffer.
struct PieceRange {
  uint32_t firstIndex = 0, indexCount = 0;
  int32_t vertexOffset = 0;  // added to its indices (0 when resident: they index the pool)
};

class TerrainGeometryBuffers {
 public:
  static constexpr int kSlots = kFramesInFlight;
  // Chunks not drawn for this many frames leave the pool (ROAM keeps idle chunks 64 outputs).
  static constexpr uint64_t kIdleFrames = 64;

  // `reserveTriangles`: the buffers' smallest size, in triangles; `tasks` may be null.
  TerrainGeometryBuffers(const Context& ctx, TaskRunner* tasks, uint64_t reserveTriangles, bool resident);

  // Writes the geometry of draws[order[k]] for every k into slot `slot`'s buffers and records the
  // copies into `cmd` (outside rendering), ending with a barrier before the vertex input and
  // compute reads. Returns each piece's range, in `order`'s order.
  std::vector<PieceRange> write(VkCommandBuffer cmd, int slot, std::span<const TerrainDraw> draws,
                                std::span<const uint32_t> order, const GrowingBuffer::Retire& retire);

  VkBuffer vertices(int slot) const;
  VkBuffer indices(int slot) const { return deviceIndices_[static_cast<size_t>(slot)].get(); }
  bool resident() const { return resident_; }
  // The last write()'s: chunks drawn and uploaded, vertices uploaded (resident only; zero when copied).
  const ChunkCacheFigures& figures() const { return cache_.figures(); }
  // The last write()'s indices gathered on the GPU from the index pool (resident only).
  uint64_t gatheredIndices() const { return indexPool_ ? indexPool_->gatheredIndices() : 0; }
  uint64_t gpuBytes() const;

 private:
  // One copy into the pool: `count` vertices from `src` (via the staging buffer at `staged`).
  struct Upload {
    const terrain::TerrainVertex* src;
    uint32_t count, poolFirst;
    uint64_t staged;
  };
  // Each writes the vertices and `idst` (the slot's host-visible indices; `ranges` from
  // indexRanges, the copied path setting their vertex offsets) and records the vertices' copies.
  void writeCopied(VkCommandBuffer cmd, size_t s, std::span<const TerrainDraw> draws, std::span<const uint32_t> order,
                   std::vector<PieceRange>& ranges, uint32_t* idst, const GrowingBuffer::Retire& retire);
  // Resident: `indices` is the frame's index count (the staging buffer also stages the uploaded
  // chunks' indices after them); the chunks drawn in full are gathered on the GPU (indexPool_).
  void writeResident(VkCommandBuffer cmd, size_t s, std::span<const TerrainDraw> draws, std::span<const uint32_t> order,
                     const std::vector<PieceRange>& ranges, uint64_t indices, const GrowingBuffer::Retire& retire);
  // writeResident's first step: every vertex range placed, the uploads listed, each chunk draw's
  // indices gathered (in full, kept in the index pool) or left to the frame thread (gathered_).
  // Returns the indices staged for the index pool's uploads.
  uint64_t placeResident(std::span<const TerrainDraw> draws, std::span<const uint32_t> order,
                         const std::vector<PieceRange>& ranges, uint64_t indices);
  // The uploads into slot `s`'s staging (at `staging`), and their copies into the pool.
  void copyUploads(VkCommandBuffer cmd, size_t s, terrain::TerrainVertex* staging, const GrowingBuffer::Retire& retire);
  void createUploadPipeline();
  // The pool holds the cache's capacity; a new buffer gets the old one's contents first.
  void growPool(VkCommandBuffer cmd, const GrowingBuffer::Retire& retire);
  // Slot `s`'s index buffers hold `indices`; returns the host-visible one's memory.
  uint32_t* ensureIndices(size_t s, uint64_t indices, const GrowingBuffer::Retire& retire);
  void recordIndexCopy(VkCommandBuffer cmd, size_t s, uint64_t indices) const;

  const Context* ctx_;
  TaskRunner* tasks_;
  bool resident_;
  std::array<GrowingBuffer, kSlots> vertices_, indices_;  // host-visible staging
  std::array<GrowingBuffer, kSlots> deviceVertices_;      // copied: each slot's vertices
  std::array<GrowingBuffer, kSlots> deviceIndices_;
  GrowingBuffer pool_;              // resident: every slot's vertices
  uint64_t poolValidVertices_ = 0;  // the pool's vertices written by earlier frames (its used part)
  TerrainChunkCache cache_;
  std::unique_ptr<TerrainIndexPool> indexPool_;  // resident only
  // Resident: the uploads' table (uvec4 each: first staged vertex, first pool vertex, vertices)
  // and the compute pipeline that scatters them into the pool.
  std::array<GrowingBuffer, kSlots> uploadTable_;
  DescriptorSetLayout uploadLayout_;
  DescriptorPool uploadPool_;
  std::array<VkDescriptorSet, kSlots> uploadSets_{};
  PipelineLayout uploadPipelineLayout_;
  Pipeline uploadPipeline_;
  // Scratch kept from frame to frame.
  std::vector<Upload> uploads_;
  std::vector<uint32_t> chunkFirst_;  // each drawn chunk's first vertex in the pool, in draw order
  std::vector<size_t> pieceChunks_;   // each piece's first entry in chunkFirst_
  std::vector<uint32_t> ownFirst_;    // each piece's own vertices' first vertex in the pool
  uint64_t stagedVertices_ = 0;       // placeResident's: vertices the uploads stage
  std::vector<uint8_t> gathered_;     // per drawn chunk, in chunkFirst_'s order: its indices come from the pool
  struct IndexUpload {
    const uint32_t* src;
    uint32_t count;
    uint64_t staged;  // in the slot's staging index buffer
  };
  std::vector<IndexUpload> indexUploads_;
};

}  // namespace vegstream::render
