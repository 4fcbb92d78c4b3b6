// The terrain's resident indices (terrain_index_pool.h).

#include "render/terrain_index_pool.h"

#include <algorithm>
#include <cassert>
#include <cstring>
#include <string>

#include "render/descriptors.h"
#include "render/pipeline_builder.h"
#include "shaders/terrain_index_copy.comp.h"

namespace vegstream::render {
namespace {
constexpr uint32_t kPerRow = 65535;  // the smallest maxComputeWorkGroupCount[0] Vulkan allows
constexpr VkBufferUsageFlags kStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
}  // namespace

TerrainIndexPool::TerrainIndexPool(const Context& ctx, TaskRunner* tasks, VkDeviceSize minimumBytes) : ctx_(&ctx) {
  pool_ = GrowingBuffer(ctx, kStorage | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                        MemoryUse::DeviceLocal, "terrain index pool", tasks, minimumBytes);
  for (size_t s = 0; s < kSlots; ++s)
    table_[s] = GrowingBuffer(ctx, kStorage, MemoryUse::HostUpload,
                              "terrain index copies (slot " + std::to_string(s) + ")", tasks, 16 * 1024);
  VkDescriptorSetLayoutBinding bindings[3];
  for (uint32_t b = 0; b < 3; ++b)
    bindings[b] = {b, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
  layout_ = createLayout(ctx, bindings, "terrain index copy layout");
  const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 3 * 2 * kSlots};
  descriptorPool_ = createPool(ctx, {&size, 1}, 2 * kSlots, "terrain index copy pool");
  allocateSlotSets(ctx, descriptorPool_.get(), layout_.get(), uploadSets_, "terrain index upload set");
  allocateSlotSets(ctx, descriptorPool_.get(), layout_.get(), gatherSets_, "terrain index gather set");
  const VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, 3 * sizeof(uint32_t)};
  const VkDescriptorSetLayout layout = layout_.get();
  pipelineLayout_ = createPipelineLayout(ctx, {&layout, 1}, {&push, 1}, "terrain index copy pipeline layout");
  pipeline_ = createComputePipeline(ctx, pipelineLayout_.get(), spv_terrain_index_copy_comp, "terrain index copy");
}

void TerrainIndexPool::beginFrame() {
  uploads_.clear();
  gathers_.clear();
  gatheredIndices_ = 0;
}

void TerrainIndexPool::upload(uint32_t stagedIndex, uint32_t count, uint32_t firstVertex) {
  assert(uint64_t{firstVertex} * kIndicesPerVertex + count <= UINT32_MAX);
  if (count > 0) uploads_.emplace_back(stagedIndex, firstVertex * kIndicesPerVertex, count, firstVertex);
}

void TerrainIndexPool::gather(uint32_t firstVertex, uint32_t first, uint32_t count, uint32_t targetIndex) {
  if (count == 0) return;
  gathers_.emplace_back(firstVertex * kIndicesPerVertex + first, targetIndex, count, 0u);
  gatheredIndices_ += count;
}

void TerrainIndexPool::recordUploads(VkCommandBuffer cmd, size_t s, VkBuffer staging, uint64_t vertexCapacity,
                                     const GrowingBuffer::Retire& retire) {
  const uint64_t capacity = vertexCapacity * kIndicesPerVertex;
  ensureKeeping(pool_, cmd, capacity * sizeof(uint32_t), poolValid_ * sizeof(uint32_t), retire);
  poolValid_ = std::max(poolValid_, capacity);
  // The table: this frame's uploads, then its gathers (recordGather reads them from there).
  const size_t entries = uploads_.size() + gathers_.size();
  table_[s].ensure(std::max<size_t>(entries, 1) * sizeof(glm::uvec4), GrowingBuffer::kNoCeiling, retire);
  auto* table = static_cast<glm::uvec4*>(table_[s].buffer().mapped);
  if (!uploads_.empty()) std::memcpy(table, uploads_.data(), uploads_.size() * sizeof(glm::uvec4));
  if (!gathers_.empty()) std::memcpy(table + uploads_.size(), gathers_.data(), gathers_.size() * sizeof(glm::uvec4));
  if (uploads_.empty()) return;
  bindOnce(uploadSets_[s], uploadBound_[s], {staging, table_[s].get(), pool_.get()});
  dispatch(cmd, uploadSets_[s], 0, static_cast<uint32_t>(uploads_.size()));
}

void TerrainIndexPool::recordGather(VkCommandBuffer cmd, size_t s, VkBuffer indices) {
  if (gathers_.empty()) return;
  // This frame's uploads into the pool and copies into `indices` before the gather reads the one
  // and writes the other.
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_COPY_BIT,
                VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT,
                VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  bindOnce(gatherSets_[s], gatherBound_[s], {pool_.get(), table_[s].get(), indices});
  dispatch(cmd, gatherSets_[s], static_cast<uint32_t>(uploads_.size()), static_cast<uint32_t>(gathers_.size()));
}

void TerrainIndexPool::bindOnce(VkDescriptorSet set, std::array<VkBuffer, 3>& bound, std::array<VkBuffer, 3> buffers) {
  // The slot's last frame has finished (its fence was waited for): its sets are free to write.
  for (uint32_t b = 0; b < 3; ++b)
    if (bound[b] != buffers[b]) writeStorageBuffer(*ctx_, set, buffers[b], b);
  bound = buffers;
}

void TerrainIndexPool::dispatch(VkCommandBuffer cmd, VkDescriptorSet set, uint32_t first, uint32_t count) {
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_.get());
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelineLayout_.get(), 0, 1, &set, 0, nullptr);
  const uint32_t push[3] = {first, count, kPerRow};
  vkCmdPushConstants(cmd, pipelineLayout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), push);
  vkCmdDispatch(cmd, std::min(count, kPerRow), (count + kPerRow - 1) / kPerRow, 1);
}

uint64_t TerrainIndexPool::gpuBytes() const {
  uint64_t bytes = pool_.size();
  for (const GrowingBuffer& t : table_) bytes += t.size();
  return bytes;
}

}  // namespace vegstream::render
