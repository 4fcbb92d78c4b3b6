#include "render/terrain_pass.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <numeric>
#include <string>
#include <utility>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "core/parallel_for.h"
#include "render/descriptors.h"
#include "render/pipeline_builder.h"
#include "render/render_targets.h"
#include "render/vk_check.h"
#include "shaders/terrain.frag.h"
#include "shaders/terrain.vert.h"
#include "shaders/terrain_vis.frag.h"
#include "shaders/terrain_vis.vert.h"

namespace vegstream::render {
namespace {
static_assert(sizeof(terrain::TerrainVertex) == 36, "must match the attributes of shaders/terrain.vert");
constexpr VkShaderStageFlags kDrawStages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
constexpr VkShaderStageFlags kSampledBy = VK_SHADER_STAGE_FRAGMENT_BIT | VK_SHADER_STAGE_COMPUTE_BIT;
constexpr VkDeviceSize kTileBytes = VkDeviceSize{kImageryTileSize} * kImageryTileSize * 4;
constexpr VkDeviceSize kCompanionBytes = VkDeviceSize{kImageryTileSize} * kImageryTileSize * 2;

// One layer's companion texels (RG8): NDVI byte, landcover class code; 0 where a layer is absent.
void interleaveCompanions(uint8_t* dst, std::span<const uint8_t> ndvi, std::span<const uint8_t> landcover) {
  constexpr size_t n = size_t{kImageryTileSize} * kImageryTileSize;
  for (size_t i = 0; i < n; ++i) {
    dst[2 * i] = ndvi.empty() ? 0 : ndvi[i];
    dst[2 * i + 1] = landcover.empty() ? 0 : landcover[i];
  }
}

// Distance from `eye` to the axis-aligned box of a mesh's vertices, its chunks' included (0
// inside it). A chunk's draw brings its box (TerrainChunkDraw::boundsMin / boundsMax): every chunk
// vertex of every piece, read each frame, was 4.7 MB a frame at 1080p (render/README.md).
double distanceToBounds(const terrain::TerrainMesh& m, const glm::dvec3& eye) {
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
  terrain::growBox(m.vertices, lo, hi);
  for (const terrain::TerrainChunkDraw& c : m.chunks) {
    if (c.vertexCount == 0) continue;
    lo = glm::min(lo, c.boundsMin);
    hi = glm::max(hi, c.boundsMax);
  }
  const glm::dvec3 local = eye - m.origin;
  const glm::dvec3 nearest = glm::clamp(local, glm::dvec3(lo), glm::dvec3(hi));
  return glm::length(local - nearest);
}

}  // namespace

std::vector<uint32_t> frontToBackOrder(std::span<const TerrainDraw> draws, const glm::dvec3& cameraPosition,
                                       TaskRunner* tasks) {
  std::vector<uint32_t> order;
  for (uint32_t i = 0; i < draws.size(); ++i)
    if (draws[i].mesh && draws[i].mesh->triangleCount() > 0) order.push_back(i);
  // The bounds read each piece's own vertices and its chunks' boxes: one task per piece.
  std::vector<double> distance(draws.size(), 0.0);
  parallelEach(order.size(), tasks,
               [&](size_t k) { distance[order[k]] = distanceToBounds(*draws[order[k]].mesh, cameraPosition); });
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return distance[a] < distance[b]; });
  return order;
}

TerrainPass::TerrainPass(const Context& ctx, VkDescriptorSetLayout frameLayout, VkSampleCountFlagBits samples,
                         bool deferred, TaskRunner* tasks, uint64_t reserveTriangles, bool residentGeometry)
    : ctx_(&ctx), tasks_(tasks), detail_(ctx, vegetation::defaultTerrainTypes()),
      geometry_(ctx, tasks, reserveTriangles, residentGeometry) {
  constexpr VkDeviceSize kSmallest = 256 * 1024;
  for (int i = 0; i < kSlots; ++i) {
    const auto s = static_cast<size_t>(i);
    const std::string tag = " (slot " + std::to_string(i) + ")";
    staging_[s] = GrowingBuffer(ctx, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::HostUpload,
                                "terrain imagery staging" + tag, tasks, kSmallest);
    pieces_[s] = GrowingBuffer(ctx, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::HostUpload, "terrain pieces" + tag,
                               tasks, kSmallest);
    drawList_[s] = GrowingBuffer(ctx, VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT, MemoryUse::HostUpload,
                                 "terrain draw list" + tag, tasks, 16 * 1024);
  }
  multiDraw_ = ctx.info().multiDrawIndirect;
  const VkDescriptorSetLayoutBinding pieceBinding{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, kDrawStages, nullptr};
  piecesLayout_ = createLayout(ctx, {&pieceBinding, 1}, "terrain pieces layout");
  const VkDescriptorPoolSize piecesPoolSize{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kSlots};
  piecesPool_ = createPool(ctx, {&piecesPoolSize, 1}, kSlots, "terrain pieces pool");
  for (auto& set : piecesSets_)
    set = allocateDescriptorSet(ctx, piecesPool_.get(), piecesLayout_.get(), "terrain pieces set");
  // Binding 0: the imagery array; 1: its NDVI array (terrain_shading.glsl).
  const VkDescriptorSetLayoutBinding imageryBindings[] = {
      {0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, kSampledBy, nullptr},
      {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, kSampledBy, nullptr}};
  imageryLayout_ = createLayout(ctx, imageryBindings, "terrain imagery layout");
  const VkDescriptorPoolSize imageryPoolSize[] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 2}};
  imageryPool_ = createPool(ctx, imageryPoolSize, 1, "terrain imagery pool");
  imagerySet_ = allocateDescriptorSet(ctx, imageryPool_.get(), imageryLayout_.get(), "terrain imagery set");
  sampler_ = createLinearClampSampler(ctx, "terrain imagery sampler");

  createPipelines(frameLayout, samples, deferred);

  // One layer until the scene says how many it streams, so the descriptor is always valid.
  setImageryLayers(1, {}, [](GpuImage&&) {});
}

void TerrainPass::createPipelines(VkDescriptorSetLayout frameLayout, VkSampleCountFlagBits samples, bool deferred) {
  const Context& ctx = *ctx_;
  const VkDescriptorSetLayout sets[] = {frameLayout, imageryLayout_.get(), detail_.layout(), piecesLayout_.get()};
  layout_ = createPipelineLayout(ctx, sets, {}, "terrain pipeline layout");
  GraphicsPipelineDesc desc;
  desc.name = "terrain pipeline";
  desc.stages = {{VK_SHADER_STAGE_VERTEX_BIT, spv_terrain_vert}, {VK_SHADER_STAGE_FRAGMENT_BIT, spv_terrain_frag}};
  desc.bindings = {{0, sizeof(terrain::TerrainVertex), VK_VERTEX_INPUT_RATE_VERTEX}};
  desc.attributes = {
      {0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(terrain::TerrainVertex, position)},
      {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(terrain::TerrainVertex, normal)},
      {2, 0, VK_FORMAT_R32_SFLOAT, offsetof(terrain::TerrainVertex, heightMsl)},
      {3, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(terrain::TerrainVertex, uv)},
  };
  desc.samples = samples;
  desc.colorFormat = kColorFormat;
  desc.depthFormat = kDepthFormat;
  desc.layout = layout_.get();
  pipeline_ = createGraphicsPipeline(ctx, desc);
  if (deferred) {
    desc.name = "terrain visibility pipeline";
    desc.stages = {{VK_SHADER_STAGE_VERTEX_BIT, spv_terrain_vis_vert},
                   {VK_SHADER_STAGE_FRAGMENT_BIT, spv_terrain_vis_frag}};
    desc.attributes.resize(1);  // the position only
    desc.colorFormat = kVisibilityFormat;
    visibilityPipeline_ = createGraphicsPipeline(ctx, desc);
  }
}

void TerrainPass::setImageryLayers(uint32_t layers, ImageryCompanions companions, const RetireImage& retire) {
  assert(layers >= 1);
  if (imagery_.image) retire(std::move(imagery_));
  if (companionArray_.image) retire(std::move(companionArray_));
  imagery_ = createImageArray(*ctx_, {kImageryTileSize, kImageryTileSize}, layers, VK_FORMAT_R8G8B8A8_SRGB,
                              VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, "terrain imagery array", 1,
                              VK_FORMAT_R8G8B8A8_UNORM);
  const uint32_t companionLayers = companions.any() ? layers : 1;
  companionArray_ =
      createImageArray(*ctx_, {kImageryTileSize, kImageryTileSize}, companionLayers, VK_FORMAT_R8G8_UNORM,
                       VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, "terrain NDVI + landcover array");
  layers_ = layers;
  companions_ = companions;
  // Every layer starts shader-readable (never sampled before its upload: the streamer hands out
  // a layer only with its tile), so uploads can move one layer at a time.
  ctx_->submitAndWait([&](VkCommandBuffer cmd) {
    transitionImageRange(cmd, imagery_.get(), {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, layers}, VK_IMAGE_LAYOUT_UNDEFINED,
                         VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, 0,
                         VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                         VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    // The companion array starts at 0 ("none"): the terrain samples it for every layer, and a
    // dataset without companions never uploads any.
    const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, companionLayers};
    transitionImageRange(cmd, companionArray_.get(), all, VK_IMAGE_LAYOUT_UNDEFINED,
                         VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, 0,
                         VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    const VkClearColorValue zero{};
    vkCmdClearColorImage(cmd, companionArray_.get(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero, 1, &all);
    transitionImageRange(cmd, companionArray_.get(), all, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                         VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_CLEAR_BIT,
                         VK_ACCESS_2_TRANSFER_WRITE_BIT,
                         VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                         VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  });
  // The caller guarantees no frame in flight uses the set (the renderer waits for idle first).
  writeSampledImage(*ctx_, imagerySet_, sampler_.get(), imagery_.view.get());
  writeSampledImage(*ctx_, imagerySet_, sampler_.get(), companionArray_.view.get(), 1);
}

void TerrainPass::recordUploads(VkCommandBuffer cmd, int slot, std::span<const ImageryUpload> uploads,
                                const RetireBuffer& retire) {
  if (uploads.empty()) return;
  const auto s = static_cast<size_t>(slot);
  const VkDeviceSize perTile = kTileBytes + (companions_.any() ? kCompanionBytes : 0);
  staging_[s].ensure(perTile * uploads.size(), GrowingBuffer::kNoCeiling, retire);
  auto* staging = static_cast<uint8_t*>(staging_[s].buffer().mapped);
  VkDeviceSize offset = 0;
  for (const ImageryUpload& u : uploads) {
    assert(u.layer < layers_ && "the streamer's slots fit the array it sized");
    // The tile-size check at the upload: only whole 256 × 256 tiles are copied.
    constexpr size_t kLayerBytes = size_t{kImageryTileSize} * kImageryTileSize;
    if (u.rgba.size() != kTileBytes || (!u.ndvi.empty() && u.ndvi.size() != kLayerBytes) ||
        (!u.landcover.empty() && u.landcover.size() != kLayerBytes))
      continue;
    std::memcpy(staging + offset, u.rgba.data(), kTileBytes);
    recordImageUpload(cmd, staging_[s].buffer(), imagery_, u.layer, offset);
    offset += kTileBytes;
    if (!companions_.any()) continue;
    // A tile without NDVI or classes clears the layer's (0: none), so no earlier tile's lingers.
    interleaveCompanions(staging + offset, u.ndvi, u.landcover);
    recordImageUpload(cmd, staging_[s].buffer(), companionArray_, u.layer, offset);
    offset += kCompanionBytes;
  }
}

uint64_t TerrainPass::prepare(VkCommandBuffer cmd, int slot, const glm::dvec3& cameraPosition,
                              std::span<const TerrainDraw> draws, const RetireBuffer& retire) {
  const auto s = static_cast<size_t>(slot);
  std::vector<VkDrawIndexedIndirectCommand>& list = draws_[s];
  list.clear();
  const std::vector<uint32_t> order = frontToBackOrder(draws, cameraPosition, tasks_);
  const std::vector<PieceRange> ranges = geometry_.write(cmd, slot, draws, order, retire);
  const size_t pieces = std::max<size_t>(order.size(), 1);
  pieces_[s].ensure(pieces * sizeof(TerrainPiece), GrowingBuffer::kNoCeiling, retire);
  drawList_[s].ensure(pieces * sizeof(VkDrawIndexedIndirectCommand), GrowingBuffer::kNoCeiling, retire);
  // The slot's last frame has finished (its fence was waited for): its set is free to write.
  writeStorageBuffer(*ctx_, piecesSets_[s], pieces_[s].get(), 0);
  auto* pdst = static_cast<TerrainPiece*>(pieces_[s].buffer().mapped);
  uint64_t triangles = 0;
  for (size_t k = 0; k < order.size(); ++k) {
    const TerrainDraw& d = draws[order[k]];
    const PieceRange& r = ranges[k];
    const bool valid = [&] {  // a layer the array does not have is a caller bug; draw uncoloured instead of faulting
      return d.imageryLayer < static_cast<int32_t>(layers_) && d.previousLayer < static_cast<int32_t>(layers_);
    }();
    assert(valid);
    // The subtraction happens in double; only the small camera-relative offset becomes float.
    pdst[k] = TerrainPiece{glm::vec4(glm::vec3(d.mesh->origin - cameraPosition), 0.0f), d.imageryUv, d.previousUv,
                           glm::vec4(valid ? static_cast<float>(d.imageryLayer) : -1.0f,
                                     valid ? static_cast<float>(d.previousLayer) : -1.0f, d.imageryBlend, 0.0f),
                           glm::uvec4(r.firstIndex / 3, static_cast<uint32_t>(r.vertexOffset), r.indexCount / 3, 0u)};
    list.push_back({r.indexCount, 1, r.firstIndex, r.vertexOffset, static_cast<uint32_t>(k)});
    triangles += r.indexCount / 3;
  }
  if (!list.empty())
    std::memcpy(drawList_[s].buffer().mapped, list.data(), list.size() * sizeof(VkDrawIndexedIndirectCommand));
  drawCount_[s] = static_cast<uint32_t>(list.size());
  return triangles;
}

void TerrainPass::recordDraws(VkCommandBuffer cmd, int slot, VkDescriptorSet frameSet, VkPipeline pipeline) const {
  const auto s = static_cast<size_t>(slot);
  if (drawCount_[s] == 0) return;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
  const VkDescriptorSet sets[] = {frameSet, imagerySet_, detail_.set(), piecesSets_[s]};
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_.get(), 0, 4, sets, 0, nullptr);
  const VkBuffer vb = geometry_.vertices(slot);
  const VkDeviceSize zero = 0;
  vkCmdBindVertexBuffers(cmd, 0, 1, &vb, &zero);
  vkCmdBindIndexBuffer(cmd, geometry_.indices(slot), 0, VK_INDEX_TYPE_UINT32);
  if (multiDraw_) {
    vkCmdDrawIndexedIndirect(cmd, drawList_[s].get(), 0, drawCount_[s], sizeof(VkDrawIndexedIndirectCommand));
    return;
  }
  for (const VkDrawIndexedIndirectCommand& d : draws_[s])
    vkCmdDrawIndexed(cmd, d.indexCount, d.instanceCount, d.firstIndex, d.vertexOffset, d.firstInstance);
}

void TerrainPass::recordForward(VkCommandBuffer cmd, int slot, VkDescriptorSet frameSet) const {
  recordDraws(cmd, slot, frameSet, pipeline_.get());
}

void TerrainPass::recordVisibility(VkCommandBuffer cmd, int slot, VkDescriptorSet frameSet) const {
  assert(visibilityPipeline_ && "built only when deferred");
  recordDraws(cmd, slot, frameSet, visibilityPipeline_.get());
}

TerrainGeometry TerrainPass::geometry(int slot) const {
  const auto s = static_cast<size_t>(slot);
  return {geometry_.vertices(slot), geometry_.indices(slot), pieces_[s].get(), drawCount_[s]};
}

uint64_t TerrainPass::gpuBytes() const {
  uint64_t bytes = imagery_.bytes + companionArray_.bytes + detail_.gpuBytes() + geometry_.gpuBytes();
  for (size_t s = 0; s < kSlots; ++s) bytes += staging_[s].size() + pieces_[s].size() + drawList_[s].size();
  return bytes;
}

}  // namespace vegstream::render
