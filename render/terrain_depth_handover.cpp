#include "render/terrain_depth_handover.h"

#include <cassert>
#include <cstring>
#include <string>

#include "render/descriptors.h"
#include "render/pipeline_builder.h"
#include "shaders/sky.vert.h"
#include "shaders/terrain_depth.frag.h"
#include "shaders/terrain_depth_edge.vert.h"
#include "shaders/terrain_depth_pixel.frag.h"
#include "shaders/terrain_depth_span.vert.h"
#include "shaders/terrain_depth_tiles.comp.h"

namespace vegstream::render {
namespace {
constexpr uint32_t kTile = 8;                          // common/terrain_raster.glsl's kRasterTile
constexpr uint32_t kMarkFine = 16, kMarkCoarse = 128;  // common/depth_tile_marks.glsl
// DepthSpans: the runs' command, the full screen's, the tiles written per pixel.
constexpr VkDeviceSize kSpanHeadBytes = 48, kFullCommandAt = 16;
// The full-screen triangle replaces the runs from this share of the tiles on: on an H100 at 1080p
// the runs of 95 % of the tiles cost 0.67 ms, the full screen 0.62 (kolob-forest, bench/README.md).
constexpr uint32_t kFullScreenPercent = 85;
constexpr VkDeviceSize kEdgeHeadBytes = 16;  // DepthEdges: the command
constexpr VkDeviceSize kReadbackBytes = 3 * sizeof(uint32_t);
constexpr VkBufferUsageFlags kStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
constexpr VkBufferUsageFlags kDrawList =
    kStorage | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT;

uint32_t cells(uint32_t pixels, uint32_t cell) { return (pixels + cell - 1) / cell; }
}  // namespace

TerrainDepthHandover::TerrainDepthHandover(const Context& ctx, VkDescriptorSetLayout frameLayout,
                                           const RenderTargets& targets, DepthTiles mode)
    : ctx_(&ctx), mode_(mode) {
  const VkExtent2D e = targets.extent();
  tilesX_ = cells(e.width, kTile);
  tilesY_ = cells(e.height, kTile);
  samples_ = static_cast<uint32_t>(targets.samples());
  const VkDeviceSize tiles = VkDeviceSize{tilesX_} * tilesY_;
  const VkDeviceSize markCells = VkDeviceSize{cells(e.width, kMarkFine)} * cells(e.height, kMarkFine) +
                                 VkDeviceSize{cells(e.width, kMarkCoarse)} * cells(e.height, kMarkCoarse);
  marks_ = createBuffer(ctx, 4 * (1 + markCells), kStorage, MemoryUse::DeviceLocal, "terrain depth tile marks");
  tileEdges_ = createBuffer(ctx, 4 * tiles, kStorage, MemoryUse::DeviceLocal, "terrain depth edge flags");
  spans_ = createBuffer(ctx, kSpanHeadBytes + 16 * tiles, kDrawList, MemoryUse::DeviceLocal, "terrain depth runs");
  edges_ = createBuffer(ctx, kEdgeHeadBytes + 4 * tiles, kDrawList, MemoryUse::DeviceLocal, "terrain depth edges");
  for (int s = 0; s < kSlots; ++s) {
    auto& r = readback_[static_cast<size_t>(s)];
    r = createBuffer(ctx, kReadbackBytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::HostReadback,
                     "terrain depth figures (slot " + std::to_string(s) + ")");
    std::memset(r.mapped, 0, kReadbackBytes);
  }

  const VkShaderStageFlags c = VK_SHADER_STAGE_COMPUTE_BIT;
  const VkDescriptorSetLayoutBinding list[] = {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, c, nullptr},   // edge flags
                                               {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, c, nullptr},   // runs
                                               {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, c, nullptr}};  // edges
  listLayout_ = createLayout(ctx, list, "terrain depth list layout");
  const VkDescriptorSetLayoutBinding draw{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_VERTEX_BIT, nullptr};
  drawLayout_ = createLayout(ctx, {&draw, 1}, "terrain depth draw layout");
  const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 5}};
  pool_ = createPool(ctx, sizes, 3, "terrain depth pool");
  listSet_ = allocateDescriptorSet(ctx, pool_.get(), listLayout_.get(), "terrain depth list");
  writeStorageBuffer(ctx, listSet_, tileEdges_.get(), 0);
  writeStorageBuffer(ctx, listSet_, spans_.get(), 1);
  writeStorageBuffer(ctx, listSet_, edges_.get(), 2);
  spanSet_ = allocateDescriptorSet(ctx, pool_.get(), drawLayout_.get(), "terrain depth runs");
  writeStorageBuffer(ctx, spanSet_, spans_.get(), 0);
  edgeSet_ = allocateDescriptorSet(ctx, pool_.get(), drawLayout_.get(), "terrain depth edges");
  writeStorageBuffer(ctx, edgeSet_, edges_.get(), 0);
  createPipelines(frameLayout, targets);
}

void TerrainDepthHandover::createPipelines(VkDescriptorSetLayout frameLayout, const RenderTargets& targets) {
  const Context& ctx = *ctx_;
  const VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, 32};
  const VkDescriptorSetLayout listSets[] = {frameLayout, listLayout_.get()};
  listPipelineLayout_ = createPipelineLayout(ctx, listSets, {&push, 1}, "terrain depth list pipeline layout");
  list_ = createComputePipeline(ctx, listPipelineLayout_.get(), spv_terrain_depth_tiles_comp, "terrain depth list");
  const VkDescriptorSetLayout drawSets[] = {frameLayout, drawLayout_.get()};
  drawPipelineLayout_ = createPipelineLayout(ctx, drawSets, {}, "terrain depth pipeline layout");
  GraphicsPipelineDesc d;
  d.name = "terrain depth pipeline (runs, per pixel)";
  d.stages = {{VK_SHADER_STAGE_VERTEX_BIT, spv_terrain_depth_span_vert},
              {VK_SHADER_STAGE_FRAGMENT_BIT, spv_terrain_depth_pixel_frag}};
  d.cullMode = VK_CULL_MODE_NONE;
  d.depthCompare = VK_COMPARE_OP_ALWAYS;  // every sample written, the far plane where the sky is
  d.samples = targets.samples();
  d.depthFormat = kDepthFormat;
  d.layout = drawPipelineLayout_.get();
  span_ = createGraphicsPipeline(ctx, d);
  d.name = "terrain depth pipeline (full screen, per pixel)";
  d.stages = {{VK_SHADER_STAGE_VERTEX_BIT, spv_sky_vert}, {VK_SHADER_STAGE_FRAGMENT_BIT, spv_terrain_depth_pixel_frag}};
  full_ = createGraphicsPipeline(ctx, d);
  d.name = "terrain depth pipeline (edges, per sample)";
  d.stages = {{VK_SHADER_STAGE_VERTEX_BIT, spv_terrain_depth_edge_vert},
              {VK_SHADER_STAGE_FRAGMENT_BIT, spv_terrain_depth_frag}};
  edge_ = createGraphicsPipeline(ctx, d);
}

void TerrainDepthHandover::recordBeginFrame(VkCommandBuffer cmd) const {
  // The previous frame's list and draws read them; then nothing marked, both lists empty.
  memoryBarrier(
      cmd,
      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT |
          VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_COPY_BIT,
      VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT,
      VK_PIPELINE_STAGE_2_CLEAR_BIT | VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  vkCmdFillBuffer(cmd, marks_.get(), 0, VK_WHOLE_SIZE, 0);
  const uint32_t spanHead[12] = {6, 0, 0, 0, 3, 0, 0, 0, 0, 0, 0, 0};  // and no row listed
  vkCmdUpdateBuffer(cmd, spans_.get(), 0, sizeof(spanHead), spanHead);
  const uint32_t edgeHead[4] = {6, 0, 0, 0};
  vkCmdUpdateBuffer(cmd, edges_.get(), 0, sizeof(edgeHead), edgeHead);
  // CLEAR | COPY: the fill counts as a clear (spec) or a copy (some validation layers).
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_CLEAR_BIT | VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
}

void TerrainDepthHandover::recordList(VkCommandBuffer cmd, VkDescriptorSet frameSet, bool everything) const {
  // The marks (tree classify, Hi-Z cull) and the raster's edge flags before the list reads them.
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  const VkDescriptorSet sets[] = {frameSet, listSet_};
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, listPipelineLayout_.get(), 0, 2, sets, 0, nullptr);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, list_.get());
  const uint32_t push[8] = {
      tilesX_, tilesY_, samples_, everything || mode_ == DepthTiles::All ? 1u : 0u, kFullScreenPercent, 0u, 0u, 0u};
  vkCmdPushConstants(cmd, listPipelineLayout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), push);
  vkCmdDispatch(cmd, tilesY_, 1, 1);  // a workgroup per row of tiles
  memoryBarrier(
      cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
      VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_COPY_BIT,
      VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT);
}

void TerrainDepthHandover::recordFigures(VkCommandBuffer cmd, int slot) const {
  const GpuBuffer& figures = readback_[static_cast<size_t>(slot)];
  const VkBufferCopy runs[] = {{4, 0, 4}, {32, 4, 4}};  // the runs' instance count, the tiles per pixel
  vkCmdCopyBuffer(cmd, spans_.get(), figures.get(), 2, runs);
  const VkBufferCopy edges{4, 8, 4};
  vkCmdCopyBuffer(cmd, edges_.get(), figures.get(), 1, &edges);
  hostReadBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
}

void TerrainDepthHandover::record(VkCommandBuffer cmd, VkDescriptorSet frameSet, const RenderTargets& targets,
                                  bool everything) const {
  recordList(cmd, frameSet, everything);
  // Checked: the tiles left out at the near plane (reverse-Z 1), where nothing drawn survives.
  targets.beginTerrainDepth(cmd,
                            mode_ == DepthTiles::Checked && !everything ? std::optional<float>(1.0f) : std::nullopt);
  VkDescriptorSet sets[] = {frameSet, spanSet_};
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, drawPipelineLayout_.get(), 0, 2, sets, 0, nullptr);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, span_.get());
  vkCmdDrawIndirect(cmd, spans_.get(), 0, 1, sizeof(VkDrawIndirectCommand));
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, full_.get());
  vkCmdDrawIndirect(cmd, spans_.get(), kFullCommandAt, 1, sizeof(VkDrawIndirectCommand));
  if (samples_ > 1) {  // one sample per pixel has no edges within a pixel
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, drawPipelineLayout_.get(), 1, 1, &edgeSet_, 0,
                            nullptr);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, edge_.get());
    vkCmdDrawIndirect(cmd, edges_.get(), 0, 1, sizeof(VkDrawIndirectCommand));
  }
  vkCmdEndRendering(cmd);
}

DepthHandoverFigures TerrainDepthHandover::figures(int slot) const {
  const auto* c = static_cast<const uint32_t*>(readback_[static_cast<size_t>(slot)].mapped);
  return {c[1], c[2]};
}

uint64_t TerrainDepthHandover::gpuBytes() const {
  uint64_t bytes = marks_.size + tileEdges_.size + spans_.size + edges_.size;
  for (const GpuBuffer& b : readback_) bytes += b.size;
  return bytes;
}

}  // namespace vegstream::render
