#include "render/terrain_raster_pass.h"

#include <algorithm>
#include <cassert>
#include <cstddef>
#include <cstring>
#include <string>

#include "render/descriptors.h"
#include "render/pipeline_builder.h"
#include "shaders/terrain_bin.comp.h"
#include "shaders/terrain_bin_scan.comp.h"
#include "shaders/terrain_raster.comp.h"
#include "shaders/terrain_raster_ms.comp.h"

namespace vegstream::render {
namespace {
constexpr uint32_t kBinGroup = 64;               // terrain_bin.comp local size
constexpr VkDeviceSize kTriangleBytes = 64;      // RasterTriangle (terrain_raster.glsl)
constexpr VkDeviceSize kCounterBytes = 4 * sizeof(uint32_t);
constexpr VkDeviceSize kReadbackBytes = kCounterBytes;
constexpr uint32_t kInitialEntriesPerTile = 32;  // grown when a frame needs more
constexpr VkBufferUsageFlags kStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;

uint32_t groups(uint64_t n, uint32_t size) { return static_cast<uint32_t>((n + size - 1) / size); }

void computeToCompute(VkCommandBuffer cmd) {
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
}
}  // namespace

TerrainRasterPass::TerrainRasterPass(const Context& ctx, VkDescriptorSetLayout frameLayout, const TerrainPass& terrain,
                                     const RenderTargets& targets, VkBuffer tileEdges)
    : ctx_(&ctx), tileEdges_(tileEdges) {
  assert(targets.deferredTerrain() && "the shade stores into the colour target's storage view");
  const VkExtent2D e = targets.extent();
  tilesX_ = (e.width + kTile - 1) / kTile;
  tilesY_ = (e.height + kTile - 1) / kTile;
  samples_ = static_cast<uint32_t>(targets.samples());
  listCapacity_ = tilesX_ * tilesY_ * kInitialEntriesPerTile;

  const VkShaderStageFlags c = VK_SHADER_STAGE_COMPUTE_BIT;
  const VkDescriptorSetLayoutBinding bindings[] = {
      {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, c, nullptr},   // vertices
      {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, c, nullptr},   // indices
      {3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, c, nullptr},   // pieces
      {4, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, c, nullptr},    // colour target
      {5, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, c, nullptr},   // raster triangles
      {6, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, c, nullptr},   // counters
      {7, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, c, nullptr},   // tile counts
      {8, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, c, nullptr},   // tile starts
      {9, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, c, nullptr},   // tile lists
      {10, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, c, nullptr},  // depth out
      {11, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, c, nullptr},  // tile edge flags
  };
  inputsLayout_ = createLayout(ctx, bindings, "terrain raster inputs layout");
  const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, kSlots},
                                        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 10 * kSlots}};
  pool_ = createPool(ctx, sizes, kSlots, "terrain raster pool");

  const uint32_t tiles = tilesX_ * tilesY_;
  tileCounts_ = createBuffer(ctx, VkDeviceSize{tiles} * 4, kStorage, MemoryUse::DeviceLocal, "terrain tile counts");
  tileStarts_ = createBuffer(ctx, VkDeviceSize{tiles} * 4, kStorage, MemoryUse::DeviceLocal, "terrain tile starts");
  tileLists_ = createBuffer(ctx, VkDeviceSize{listCapacity_} * 4, kStorage, MemoryUse::DeviceLocal,
                            "terrain tile lists");
  // Device-local: the binning counts with atomics, which host-visible memory would send over the bus.
  counters_ = createBuffer(ctx, kCounterBytes, kStorage | VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::DeviceLocal,
                           "terrain raster counters");
  depth_ = createBuffer(ctx, VkDeviceSize{e.width} * e.height * samples_ * sizeof(float), kStorage,
                        MemoryUse::DeviceLocal, "terrain depth samples");
  for (int s = 0; s < kSlots; ++s) {
    const auto i = static_cast<size_t>(s);
    const std::string tag = " (slot " + std::to_string(s) + ")";
    inputs_[i] = allocateDescriptorSet(ctx, pool_.get(), inputsLayout_.get(), "terrain raster inputs" + tag);
    readback_[i] = createBuffer(ctx, kReadbackBytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::HostReadback,
                                "terrain raster figures" + tag);
    std::memset(readback_[i].mapped, 0, kReadbackBytes);
  }

  createPipelines(frameLayout, terrain, targets);
}

void TerrainRasterPass::createPipelines(VkDescriptorSetLayout frameLayout, const TerrainPass& terrain,
                                        const RenderTargets& targets) {
  const Context& ctx = *ctx_;
  const VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(TerrainComputePush)};
  const VkDescriptorSetLayout sets[] = {frameLayout, terrain.imageryLayout(), terrain.detail().layout(),
                                        inputsLayout_.get()};
  layout_ = createPipelineLayout(ctx, sets, {&push, 1}, "terrain raster pipeline layout");
  bin_ = createComputePipeline(ctx, layout_.get(), spv_terrain_bin_comp, "terrain bin");
  scan_ = createComputePipeline(ctx, layout_.get(), spv_terrain_bin_scan_comp, "terrain bin scan");
  raster_ = targets.multisampled()
                ? createComputePipeline(ctx, layout_.get(), spv_terrain_raster_ms_comp, "terrain raster (MSAA)")
                : createComputePipeline(ctx, layout_.get(), spv_terrain_raster_comp, "terrain raster");
}

void TerrainRasterPass::ensureCapacity(GpuBuffer& buffer, VkDeviceSize bytes, const char* what,
                                       const RetireBuffer& retire) {
  if (buffer.buffer && buffer.size >= bytes) return;
  if (buffer.buffer) retire(std::move(buffer));
  buffer = createBuffer(*ctx_, grownSize(bytes, 256 * 1024), kStorage, MemoryUse::DeviceLocal, what);
}

void TerrainRasterPass::growLists(int slot, uint64_t triangles, const RetireBuffer& retire) {
  // Room for 4 tiles per raster triangle (most touch 1 or 2); and the slot's previous frame has
  // finished (the renderer waited for its fence): its figures say whether the lists were short
  // even so (huge triangles), and then the next frames get 1.5 × what it needed.
  const TerrainRasterFigures last = figures(slot);
  const uint64_t wanted = std::max<uint64_t>({8 * triangles, uint64_t{last.tileEntries} + last.tileEntries / 2,
                                               uint64_t{tilesX_} * tilesY_ * kInitialEntriesPerTile});
  if (wanted > listCapacity_ && (last.tileEntries > listCapacity_ || 8 * triangles > listCapacity_)) {
    listCapacity_ = static_cast<uint32_t>(std::min<uint64_t>(wanted, UINT32_MAX / 4));
    retire(std::move(tileLists_));
    tileLists_ = createBuffer(*ctx_, VkDeviceSize{listCapacity_} * 4, kStorage, MemoryUse::DeviceLocal,
                              "terrain tile lists");
  }
  // A triangle clipped by the near plane may become two.
  ensureCapacity(triangles_, std::max<VkDeviceSize>(2 * triangles, 1) * kTriangleBytes, "terrain raster triangles",
                 retire);
}

void TerrainRasterPass::writeInputs(size_t s, const TerrainGeometry& g, const RenderTargets& targets) {
  const VkDescriptorSet inputs = inputs_[s];
  writeStorageBuffer(*ctx_, inputs, g.vertices, 1);
  writeStorageBuffer(*ctx_, inputs, g.indices, 2);
  writeStorageBuffer(*ctx_, inputs, g.pieces, 3);
  writeStorageImage(*ctx_, inputs, targets.colorStorageView(), 4);
  writeStorageBuffer(*ctx_, inputs, triangles_.get(), 5);
  writeStorageBuffer(*ctx_, inputs, counters_.get(), 6);
  writeStorageBuffer(*ctx_, inputs, tileCounts_.get(), 7);
  writeStorageBuffer(*ctx_, inputs, tileStarts_.get(), 8);
  writeStorageBuffer(*ctx_, inputs, tileLists_.get(), 9);
  writeStorageBuffer(*ctx_, inputs, depth_.get(), 10);
  writeStorageBuffer(*ctx_, inputs, tileEdges_, 11);
}

void TerrainRasterPass::recordBinning(VkCommandBuffer cmd, TerrainComputePush& push, uint64_t triangles) {
  const auto pushNow = [&] {
    vkCmdPushConstants(cmd, layout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
  };
  if (triangles > 0) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, bin_.get());
    pushNow();
    vkCmdDispatch(cmd, groups(triangles, kBinGroup), 1, 1);
    computeToCompute(cmd);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, scan_.get());
    vkCmdDispatch(cmd, 1, 1, 1);
    computeToCompute(cmd);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, bin_.get());
    push.counts.z = 1;
    pushNow();
    vkCmdDispatch(cmd, groups(2 * triangles, kBinGroup), 1, 1);
    computeToCompute(cmd);
  }
}

void TerrainRasterPass::resetCounts(VkCommandBuffer cmd) const {
  // The previous frame's compute readers (its raster, Hi-Z build, the hand-over's list) before
  // this frame's writes (its fragments' reads of the depth samples are waited for at its end:
  // recordEndOfFrame); then the counts start at zero.
  memoryBarrier(cmd,
                VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT |
                    VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_COPY_BIT,
                VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT |
                    VK_ACCESS_2_TRANSFER_READ_BIT,
                VK_PIPELINE_STAGE_2_CLEAR_BIT | VK_PIPELINE_STAGE_2_COPY_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  vkCmdFillBuffer(cmd, tileCounts_.get(), 0, VK_WHOLE_SIZE, 0);
  vkCmdFillBuffer(cmd, counters_.get(), 0, kCounterBytes, 0);
  // CLEAR | COPY: the fill counts as a clear (spec) or a copy (some validation layers).
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_CLEAR_BIT | VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
}

void TerrainRasterPass::record(VkCommandBuffer cmd, int slot, VkDescriptorSet frameSet, const TerrainPass& terrain,
                               const RenderTargets& targets, uint64_t triangles, const RetireBuffer& retire,
                               const std::function<void()>& binned) {
  const auto s = static_cast<size_t>(slot);
  growLists(slot, triangles, retire);

  const TerrainGeometry g = terrain.geometry(slot);
  assert(g.vertices && g.indices && g.pieces && "TerrainPass::prepare first");
  writeInputs(s, g, targets);

  resetCounts(cmd);

  const VkDescriptorSet sets[] = {frameSet, terrain.imagerySet(), terrain.detail().set(), inputs_[s]};
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.get(), 0, 4, sets, 0, nullptr);
  TerrainComputePush push{glm::uvec4(g.pieceCount, static_cast<uint32_t>(triangles), 0u, listCapacity_),
                          glm::uvec4(tilesX_, tilesY_, samples_, 0u)};
  const auto pushNow = [&] {
    vkCmdPushConstants(cmd, layout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
  };
  recordBinning(cmd, push, triangles);
  binned();

  // The colour target becomes writable by compute (its old contents discarded: every sample is
  // written, sky included).
  const GpuImage& colour = targets.colorAttachment();
  transitionImage(cmd, colour.get(), colour.aspect, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                  VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                  VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, raster_.get());
  pushNow();
  vkCmdDispatch(cmd, tilesX_, tilesY_, 1);
  // The depth samples → the Hi-Z build and every fragment drawn over the terrain; the edge flags →
  // the depth hand-over's list; the counters → the host (figures).
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT |
                    VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT,
                VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT);
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
  const VkBufferCopy copy{0, 0, kCounterBytes};
  vkCmdCopyBuffer(cmd, counters_.get(), readback_[s].get(), 1, &copy);
  hostReadBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
}

void TerrainRasterPass::recordEndOfFrame(VkCommandBuffer cmd) const {
  // This frame's fragments and Hi-Z build read the depth samples the next frame's raster writes.
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                VK_ACCESS_2_SHADER_STORAGE_READ_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
}

TerrainRasterFigures TerrainRasterPass::figures(int slot) const {
  const auto* c = static_cast<const uint32_t*>(readback_[static_cast<size_t>(slot)].mapped);
  return {c[0], c[1], c[2]};
}

uint64_t TerrainRasterPass::gpuBytes() const {
  uint64_t bytes = triangles_.size + tileCounts_.size + tileStarts_.size + tileLists_.size + depth_.size +
                   counters_.size;
  for (const GpuBuffer& b : readback_) bytes += b.size;
  return bytes;
}

}  // namespace vegstream::render
