// The terrain's geometry buffers (terrain_geometry_buffers.h).

#include "render/terrain_geometry_buffers.h"

#include <algorithm>
#include <cassert>
#include <cstring>
#include <string>

#include "core/parallel_for.h"
#include "render/descriptors.h"
#include "render/pipeline_builder.h"
#include "render/render_targets.h"
#include "shaders/terrain_upload.comp.h"

namespace vegstream::render {
namespace {
using terrain::TerrainVertex;
constexpr VkDeviceSize kVertexBytes = sizeof(TerrainVertex);
constexpr VkDeviceSize kSmallest = 256 * 1024;
// What writes the geometry: copy commands, and the resident uploads' compute dispatch.
constexpr VkPipelineStageFlags2 kWriteStages = VK_PIPELINE_STAGE_2_COPY_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
constexpr VkAccessFlags2 kWriteAccess = VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
constexpr VkBufferUsageFlags kRead = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;

// The vertices of `m` when flattened: its own and its chunks'.
size_t flatVertices(const terrain::TerrainMesh& m) {
  size_t n = m.vertices.size();
  for (const terrain::TerrainChunkDraw& c : m.chunks) n += c.vertexCount;
  return n;
}

// Flattens `m` into vdst / idst (its own vertices, then each chunk's, indices rebased), so a
// piece stays one draw.
void copyFlat(const terrain::TerrainMesh& m, TerrainVertex* vdst, uint32_t* idst) {
  std::memcpy(vdst, m.vertices.data(), m.vertices.size() * kVertexBytes);
  std::memcpy(idst, m.indices.data(), m.indices.size() * sizeof(uint32_t));
  auto base = static_cast<uint32_t>(m.vertices.size());
  size_t at = m.indices.size();
  for (const terrain::TerrainChunkDraw& c : m.chunks) {
    const std::vector<TerrainVertex>& v = c.chunk->vertices;
    std::memcpy(vdst + base, v.data(), v.size() * kVertexBytes);
    const uint32_t* src = c.chunk->indices.data();
    for (uint32_t i = 0; i < c.count; ++i) idst[at + i] = src[i] + base;
    at += c.count;
    base += static_cast<uint32_t>(v.size());
  }
}

// Each piece's range of the index buffer, in order; the total in `indices`.
std::vector<PieceRange> indexRanges(std::span<const TerrainDraw> draws, std::span<const uint32_t> order,
                                    uint64_t& indices) {
  std::vector<PieceRange> ranges(order.size());
  indices = 0;
  for (size_t k = 0; k < order.size(); ++k) {
    ranges[k].firstIndex = static_cast<uint32_t>(indices);
    ranges[k].indexCount = static_cast<uint32_t>(draws[order[k]].mesh->triangleCount() * 3);
    indices += ranges[k].indexCount;
  }
  return ranges;
}

}  // namespace

TerrainGeometryBuffers::TerrainGeometryBuffers(const Context& ctx, TaskRunner* tasks, uint64_t reserveTriangles,
                                               bool resident)
    : ctx_(&ctx), tasks_(tasks), resident_(resident), cache_(kSlots, kIdleFrames) {
  // ROAM's chunked meshes hold 1.0–1.5 vertices a triangle on the benchmark flights.
  const VkDeviceSize vertexMin = std::max<VkDeviceSize>(reserveTriangles * 3 / 2 * kVertexBytes, kSmallest);
  const VkDeviceSize indexMin = std::max<VkDeviceSize>(reserveTriangles * 3 * sizeof(uint32_t), kSmallest);
  auto make = [&](VkBufferUsageFlags usage, MemoryUse use, const std::string& what, VkDeviceSize minimum) {
    return GrowingBuffer(ctx, usage, use, "terrain " + what, tasks, minimum);
  };
  for (size_t s = 0; s < kSlots; ++s) {
    const std::string tag = " (slot " + std::to_string(s) + ")";
    // Resident frames stage only what changed: a smaller start.
    vertices_[s] = make(VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::HostUpload,
                        "vertices" + tag, resident ? kSmallest : vertexMin);
    if (resident)
      uploadTable_[s] = make(VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::HostUpload, "uploads" + tag, 16 * 1024);
    // Storage too: the index pool's uploads read the chunks' indices staged after the frame's.
    indices_[s] = make(VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::HostUpload,
                       "indices" + tag, indexMin);
    deviceIndices_[s] = make(VK_BUFFER_USAGE_INDEX_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | kRead,
                             MemoryUse::DeviceLocal, "indices (device)" + tag, indexMin);
    if (!resident)
      deviceVertices_[s] =
          make(VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | kRead, MemoryUse::DeviceLocal, "vertices (device)" + tag, vertexMin);
  }
  if (resident)
    pool_ = make(VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | kRead, MemoryUse::DeviceLocal,
                 "vertex pool", vertexMin * 2);
  if (resident) {
    createUploadPipeline();
    indexPool_ = std::make_unique<TerrainIndexPool>(ctx, tasks, indexMin * 2);
  }
}

std::vector<PieceRange> TerrainGeometryBuffers::write(VkCommandBuffer cmd, int slot, std::span<const TerrainDraw> draws,
                                                      std::span<const uint32_t> order,
                                                      const GrowingBuffer::Retire& retire) {
  const auto s = static_cast<size_t>(slot);
  uint64_t indices = 0;
  std::vector<PieceRange> ranges = indexRanges(draws, order, indices);
  if (resident_)
    writeResident(cmd, s, draws, order, ranges, indices, retire);
  else
    writeCopied(cmd, s, draws, order, ranges, ensureIndices(s, indices, retire), retire);
  recordIndexCopy(cmd, s, indices);
  if (resident_) indexPool_->recordGather(cmd, s, deviceIndices_[s].get());
  memoryBarrier(
      cmd, kWriteStages, kWriteAccess,
      VK_PIPELINE_STAGE_2_VERTEX_ATTRIBUTE_INPUT_BIT | VK_PIPELINE_STAGE_2_INDEX_INPUT_BIT |
          VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
      VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT | VK_ACCESS_2_INDEX_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
  return ranges;
}

uint32_t* TerrainGeometryBuffers::ensureIndices(size_t s, uint64_t indices, const GrowingBuffer::Retire& retire) {
  // The buffers exist even for a frame without terrain: the shade pass's descriptors need them.
  const VkDeviceSize bytes = std::max<VkDeviceSize>(indices, 3) * sizeof(uint32_t);
  indices_[s].ensure(bytes, GrowingBuffer::kNoCeiling, retire);
  deviceIndices_[s].ensure(bytes, GrowingBuffer::kNoCeiling, retire);
  return static_cast<uint32_t*>(indices_[s].buffer().mapped);
}

void TerrainGeometryBuffers::recordIndexCopy(VkCommandBuffer cmd, size_t s, uint64_t indices) const {
  if (indices == 0) return;
  const VkBufferCopy copy{0, 0, VkDeviceSize{indices} * sizeof(uint32_t)};
  vkCmdCopyBuffer(cmd, indices_[s].get(), deviceIndices_[s].get(), 1, &copy);
}

void TerrainGeometryBuffers::writeCopied(VkCommandBuffer cmd, size_t s, std::span<const TerrainDraw> draws,
                                         std::span<const uint32_t> order, std::vector<PieceRange>& ranges,
                                         uint32_t* idst, const GrowingBuffer::Retire& retire) {
  uint64_t vertices = 0;
  for (size_t k = 0; k < order.size(); ++k) {
    ranges[k].vertexOffset = static_cast<int32_t>(vertices);
    vertices += flatVertices(*draws[order[k]].mesh);
  }
  const VkDeviceSize vertexBytes = std::max<VkDeviceSize>(vertices, 1) * kVertexBytes;
  vertices_[s].ensure(vertexBytes, GrowingBuffer::kNoCeiling, retire);
  deviceVertices_[s].ensure(vertexBytes, GrowingBuffer::kNoCeiling, retire);
  auto* vdst = static_cast<TerrainVertex*>(vertices_[s].buffer().mapped);
  parallelEach(order.size(), tasks_, [&](size_t k) {
    copyFlat(*draws[order[k]].mesh, vdst + ranges[k].vertexOffset, idst + ranges[k].firstIndex);
  });
  if (vertices > 0) {
    const VkBufferCopy vcopy{0, 0, vertices * kVertexBytes};
    vkCmdCopyBuffer(cmd, vertices_[s].get(), deviceVertices_[s].get(), 1, &vcopy);
  }
}

uint64_t TerrainGeometryBuffers::placeResident(std::span<const TerrainDraw> draws, std::span<const uint32_t> order,
                                               const std::vector<PieceRange>& ranges, uint64_t indices) {
  uint64_t staged = 0, stagedIndices = 0;
  // Where everything goes, in draw order (the cache's ranges depend on the order of its calls).
  uploads_.clear();
  indexUploads_.clear();
  chunkFirst_.clear();
  gathered_.clear();
  pieceChunks_.assign(order.size(), 0);
  ownFirst_.assign(order.size(), 0);
  cache_.beginFrame();
  indexPool_->beginFrame();
  for (size_t k = 0; k < order.size(); ++k) {
    const terrain::TerrainMesh& m = *draws[order[k]].mesh;
    if (const auto own = static_cast<uint32_t>(m.vertices.size()); own > 0) {
      ownFirst_[k] = cache_.placeTransient(own);
      uploads_.push_back({m.vertices.data(), own, ownFirst_[k], staged});
      staged += own;
    }
    pieceChunks_[k] = chunkFirst_.size();
    auto target = static_cast<uint32_t>(ranges[k].firstIndex + m.indices.size());
    for (const terrain::TerrainChunkDraw& c : m.chunks) {
      // From the draw's copy of the chunk's header: the chunk itself is read only to upload it.
      const ChunkPlacement p = cache_.place(c.id, c.version, c.vertexCount);
      const uint32_t n = c.vertexCount;
      chunkFirst_.push_back(p.firstVertex);
      // c.count is all its indices: whether the pool keeps them.
      assert(c.count == c.chunk->indices.size() && n == c.chunk->vertices.size());
      gathered_.push_back(c.count <= uint64_t{TerrainIndexPool::kIndicesPerVertex} * n ? 1 : 0);
      if (gathered_.back()) indexPool_->gather(p.firstVertex, 0, c.count, target);
      target += c.count;
      if (!p.upload || n == 0) continue;
      uploads_.push_back({c.chunk->vertices.data(), n, p.firstVertex, staged});
      staged += n;
      // Not kept: its indices are written by the frame thread whenever it is drawn.
      if (!TerrainIndexPool::fits(*c.chunk)) continue;
      const auto ni = static_cast<uint32_t>(c.chunk->indices.size());
      indexPool_->upload(static_cast<uint32_t>(indices + stagedIndices), ni, p.firstVertex);
      indexUploads_.push_back({c.chunk->indices.data(), ni, indices + stagedIndices});
      stagedIndices += ni;
    }
  }
  cache_.endFrame();
  stagedVertices_ = staged;
  return stagedIndices;
}

void TerrainGeometryBuffers::writeResident(VkCommandBuffer cmd, size_t s, std::span<const TerrainDraw> draws,
                                           std::span<const uint32_t> order, const std::vector<PieceRange>& ranges,
                                           uint64_t indices, const GrowingBuffer::Retire& retire) {
  const uint64_t stagedIndices = placeResident(draws, order, ranges, indices);
  uint32_t* idst = ensureIndices(s, indices + stagedIndices, retire);
  growPool(cmd, retire);
  vertices_[s].ensure(std::max<VkDeviceSize>(stagedVertices_, 1) * kVertexBytes, GrowingBuffer::kNoCeiling, retire);
  auto* vdst = static_cast<TerrainVertex*>(vertices_[s].buffer().mapped);
  // The indices the frame thread writes: the pieces' own, and those of a chunk the index pool
  // does not keep (more than kIndicesPerVertex a vertex: none of ROAM's).
  parallelEach(order.size(), tasks_, [&](size_t k) {
    const terrain::TerrainMesh& m = *draws[order[k]].mesh;
    uint32_t* out = idst + ranges[k].firstIndex;
    for (uint32_t i : m.indices) *out++ = i + ownFirst_[k];
    for (size_t j = 0; j < m.chunks.size(); ++j) {
      const size_t at = pieceChunks_[k] + j;
      if (!gathered_[at]) {
        const uint32_t base = chunkFirst_[at];
        const uint32_t* src = m.chunks[j].chunk->indices.data();
        for (uint32_t i = 0; i < m.chunks[j].count; ++i) out[i] = src[i] + base;
      }
      out += m.chunks[j].count;
    }
  });
  // The uploaded chunks' indices, staged for the index pool: a few hundred kilobytes at most, on
  // this thread (a parallel loop's hand-over to a 16-core pool costs more than the copies).
  for (const IndexUpload& u : indexUploads_) std::memcpy(idst + u.staged, u.src, u.count * sizeof(uint32_t));
  copyUploads(cmd, s, vdst, retire);
  indexPool_->recordUploads(cmd, s, indices_[s].get(), cache_.capacity(), retire);
}

void TerrainGeometryBuffers::copyUploads(VkCommandBuffer cmd, size_t s, TerrainVertex* staging,
                                         const GrowingBuffer::Retire& retire) {
  parallelEach(uploads_.size(), tasks_, [&](size_t u) {
    std::memcpy(staging + uploads_[u].staged, uploads_[u].src, uploads_[u].count * kVertexBytes);
  });
  if (uploads_.empty()) return;
  uploadTable_[s].ensure(uploads_.size() * sizeof(glm::uvec4), GrowingBuffer::kNoCeiling, retire);
  auto* table = static_cast<glm::uvec4*>(uploadTable_[s].buffer().mapped);
  for (size_t u = 0; u < uploads_.size(); ++u)
    table[u] = glm::uvec4(static_cast<uint32_t>(uploads_[u].staged), uploads_[u].poolFirst, uploads_[u].count, 0u);
  // The slot's last frame has finished (its fence was waited for): its set is free to write.
  writeStorageBuffer(*ctx_, uploadSets_[s], vertices_[s].get(), 0);
  writeStorageBuffer(*ctx_, uploadSets_[s], uploadTable_[s].get(), 1);
  writeStorageBuffer(*ctx_, uploadSets_[s], pool_.get(), 2);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, uploadPipeline_.get());
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, uploadPipelineLayout_.get(), 0, 1, &uploadSets_[s], 0,
                          nullptr);
  constexpr uint32_t kPerRow = 65535;  // the smallest maxComputeWorkGroupCount[0] Vulkan allows
  const auto count = static_cast<uint32_t>(uploads_.size());
  const uint32_t push[2] = {count, kPerRow};
  vkCmdPushConstants(cmd, uploadPipelineLayout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), push);
  vkCmdDispatch(cmd, std::min(count, kPerRow), (count + kPerRow - 1) / kPerRow, 1);
}

void TerrainGeometryBuffers::createUploadPipeline() {
  const Context& ctx = *ctx_;
  VkDescriptorSetLayoutBinding bindings[3];
  for (uint32_t b = 0; b < 3; ++b)
    bindings[b] = {b, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
  uploadLayout_ = createLayout(ctx, bindings, "terrain upload layout");
  const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 3 * kSlots};
  uploadPool_ = createPool(ctx, {&size, 1}, kSlots, "terrain upload pool");
  allocateSlotSets(ctx, uploadPool_.get(), uploadLayout_.get(), uploadSets_, "terrain upload set");
  const VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, 2 * sizeof(uint32_t)};
  const VkDescriptorSetLayout layout = uploadLayout_.get();
  uploadPipelineLayout_ = createPipelineLayout(ctx, {&layout, 1}, {&push, 1}, "terrain upload pipeline layout");
  uploadPipeline_ = createComputePipeline(ctx, uploadPipelineLayout_.get(), spv_terrain_upload_comp, "terrain upload");
}

void TerrainGeometryBuffers::growPool(VkCommandBuffer cmd, const GrowingBuffer::Retire& retire) {
  ensureKeeping(pool_, cmd, cache_.capacity() * kVertexBytes, poolValidVertices_ * kVertexBytes, retire);
  poolValidVertices_ = cache_.capacity();
}

VkBuffer TerrainGeometryBuffers::vertices(int slot) const {
  return resident_ ? pool_.get() : deviceVertices_[static_cast<size_t>(slot)].get();
}

uint64_t TerrainGeometryBuffers::gpuBytes() const {
  uint64_t bytes = pool_.size() + (indexPool_ ? indexPool_->gpuBytes() : 0);
  for (size_t s = 0; s < kSlots; ++s)
    bytes += vertices_[s].size() + indices_[s].size() + deviceIndices_[s].size() + deviceVertices_[s].size();
  return bytes;
}

}  // namespace vegstream::render
