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
constexpr VkShaderStageFlags kPushStages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
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

// A mesh's vertices and indices when flattened: its own and its chunks' (terrain_mesh.h).
struct MeshSize {
  size_t vertices = 0, indices = 0;
};
MeshSize flatSize(const terrain::TerrainMesh& m) {
  MeshSize s{m.vertices.size(), m.indices.size()};
  for (const terrain::TerrainChunkDraw& c : m.chunks) {
    s.vertices += c.chunk->vertices.size();
    s.indices += c.count;
  }
  return s;
}

// The drawn pieces, in draw order: each one's size (counted once, used twice) and range of the
// buffers (first vertex, first index); their totals.
struct PieceLayout {
  std::vector<MeshSize> sizes;
  std::vector<std::pair<uint32_t, uint32_t>> at;
  VkDeviceSize vertexBytes = 0, indexBytes = 0;
  uint32_t vertices = 0, indices = 0;
};

PieceLayout layoutPieces(std::span<const TerrainDraw> draws, const std::vector<uint32_t>& order) {
  PieceLayout l;
  l.sizes.reserve(order.size());
  for (uint32_t i : order) {
    const MeshSize size = l.sizes.emplace_back(flatSize(*draws[i].mesh));
    l.vertexBytes += size.vertices * sizeof(terrain::TerrainVertex);
    l.indexBytes += size.indices * sizeof(uint32_t);
  }
  l.at.resize(order.size());
  for (size_t k = 0; k < order.size(); ++k) {
    l.at[k] = {l.vertices, l.indices};
    l.vertices += static_cast<uint32_t>(l.sizes[k].vertices);
    l.indices += static_cast<uint32_t>(l.sizes[k].indices);
  }
  return l;
}

// Flattens `m` into vdst / idst (its own vertices, then each chunk's, indices rebased), so a
// piece stays one draw. The chunks are copied every frame, like the rest of the geometry.
void copyFlat(const terrain::TerrainMesh& m, terrain::TerrainVertex* vdst, uint32_t* idst) {
  std::memcpy(vdst, m.vertices.data(), m.vertices.size() * sizeof(terrain::TerrainVertex));
  std::memcpy(idst, m.indices.data(), m.indices.size() * sizeof(uint32_t));
  auto base = static_cast<uint32_t>(m.vertices.size());
  size_t at = m.indices.size();
  for (const terrain::TerrainChunkDraw& c : m.chunks) {
    const std::vector<terrain::TerrainVertex>& v = c.chunk->vertices;
    std::memcpy(vdst + base, v.data(), v.size() * sizeof(terrain::TerrainVertex));
    const uint32_t* src = (c.partial ? m.chunkIndices.data() : c.chunk->indices.data()) + c.first;
    for (uint32_t i = 0; i < c.count; ++i) idst[at + i] = src[i] + base;
    at += c.count;
    base += static_cast<uint32_t>(v.size());
  }
}

// Distance from `eye` to the axis-aligned box of a mesh's vertices, its chunks' included (0
// inside it).
double distanceToBounds(const terrain::TerrainMesh& m, const glm::dvec3& eye) {
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
  const auto grow = [&](const std::vector<terrain::TerrainVertex>& vertices) {
    for (const terrain::TerrainVertex& v : vertices) {
      lo = glm::min(lo, v.position);
      hi = glm::max(hi, v.position);
    }
  };
  grow(m.vertices);
  for (const terrain::TerrainChunkDraw& c : m.chunks) grow(c.chunk->vertices);
  const glm::dvec3 local = eye - m.origin;
  const glm::dvec3 nearest = glm::clamp(local, glm::dvec3(lo), glm::dvec3(hi));
  return glm::length(local - nearest);
}

// work(k) for k in [0, n) on `tasks` and the calling thread (all on it without a runner).
void eachPiece(size_t n, TaskRunner* tasks, const std::function<void(size_t)>& work) {
  const Status s = parallelFor(n, tasks ? 0 : 1, tasks, [&](size_t k) -> Status {
    work(k);
    return {};
  });
  assert(s.ok());
  (void)s;
}

}  // namespace

std::vector<uint32_t> frontToBackOrder(std::span<const TerrainDraw> draws, const glm::dvec3& cameraPosition,
                                       TaskRunner* tasks) {
  std::vector<uint32_t> order;
  for (uint32_t i = 0; i < draws.size(); ++i)
    if (draws[i].mesh && flatSize(*draws[i].mesh).indices > 0) order.push_back(i);
  // The bounds read every vertex: one task per piece.
  std::vector<double> distance(draws.size(), 0.0);
  eachPiece(order.size(), tasks, [&](size_t k) {
    distance[order[k]] = distanceToBounds(*draws[order[k]].mesh, cameraPosition);
  });
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return distance[a] < distance[b]; });
  return order;
}

TerrainPass::TerrainPass(const Context& ctx, VkDescriptorSetLayout frameLayout, VkSampleCountFlagBits samples,
                         bool deferred, TaskRunner* tasks, uint64_t reserveTriangles)
    : ctx_(&ctx), tasks_(tasks), detail_(ctx, vegetation::defaultTerrainTypes()) {
  // The slots' buffers, made as frames need them (growing_buffer.h); the geometry ones at least
  // as large as `reserveTriangles` need (ROAM's chunked meshes hold 1.0–1.5 vertices a triangle
  // on the benchmark flights).
  constexpr VkDeviceSize kSmallest = 256 * 1024;
  const VkDeviceSize vertexMin = std::max<VkDeviceSize>(reserveTriangles * 3 / 2 * sizeof(terrain::TerrainVertex), kSmallest);
  const VkDeviceSize indexMin = std::max<VkDeviceSize>(reserveTriangles * 3 * sizeof(uint32_t), kSmallest);
  constexpr VkBufferUsageFlags kRead = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  for (int i = 0; i < kSlots; ++i) {
    const auto s = static_cast<size_t>(i);
    const std::string tag = " (slot " + std::to_string(i) + ")";
    auto make = [&](VkBufferUsageFlags usage, MemoryUse use, const char* what, VkDeviceSize minimum) {
      return GrowingBuffer(ctx, usage, use, std::string("terrain ") + what + tag, tasks, minimum);
    };
    staging_[s] = make(VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::HostUpload, "imagery staging", kSmallest);
    vertices_[s] = make(VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::HostUpload, "vertices", vertexMin);
    indices_[s] = make(VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::HostUpload, "indices", indexMin);
    deviceVertices_[s] =
        make(VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | kRead, MemoryUse::DeviceLocal, "vertices (device)", vertexMin);
    deviceIndices_[s] =
        make(VK_BUFFER_USAGE_INDEX_BUFFER_BIT | kRead, MemoryUse::DeviceLocal, "indices (device)", indexMin);
    pieces_[s] = make(VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::HostUpload, "pieces", kSmallest);
  }
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
  const VkPushConstantRange push{kPushStages, 0, sizeof(TerrainPush)};
  const VkDescriptorSetLayout sets[] = {frameLayout, imageryLayout_.get(), detail_.layout()};
  layout_ = createPipelineLayout(ctx, sets, {&push, 1}, "terrain pipeline layout");
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
    transitionImageRange(cmd, companionArray_.get(), all, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                         VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
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
  std::vector<PreparedDraw>& list = prepared_[s];
  list.clear();
  const std::vector<uint32_t> order = frontToBackOrder(draws, cameraPosition, tasks_);
  const PieceLayout layout = layoutPieces(draws, order);
  const auto& at = layout.at;
  VkDeviceSize vertexBytes = layout.vertexBytes, indexBytes = layout.indexBytes;
  // The buffers exist even for a frame without terrain: the shade pass's descriptors need them.
  vertexBytes = std::max<VkDeviceSize>(vertexBytes, sizeof(terrain::TerrainVertex));
  indexBytes = std::max<VkDeviceSize>(indexBytes, 3 * sizeof(uint32_t));
  vertices_[s].ensure(vertexBytes, GrowingBuffer::kNoCeiling, retire);
  indices_[s].ensure(indexBytes, GrowingBuffer::kNoCeiling, retire);
  deviceVertices_[s].ensure(vertexBytes, GrowingBuffer::kNoCeiling, retire);
  deviceIndices_[s].ensure(indexBytes, GrowingBuffer::kNoCeiling, retire);
  pieces_[s].ensure(std::max<size_t>(order.size(), 1) * sizeof(TerrainPiece), GrowingBuffer::kNoCeiling, retire);
  if (order.empty()) return 0;

  auto* vdst = static_cast<uint8_t*>(vertices_[s].buffer().mapped);
  auto* idst = static_cast<uint8_t*>(indices_[s].buffer().mapped);
  auto* pdst = static_cast<TerrainPiece*>(pieces_[s].buffer().mapped);
  // The copies, a task per piece.
  eachPiece(order.size(), tasks_, [&](size_t k) {
    copyFlat(*draws[order[k]].mesh, reinterpret_cast<terrain::TerrainVertex*>(vdst) + at[k].first,
             reinterpret_cast<uint32_t*>(idst) + at[k].second);
  });
  for (size_t k = 0; k < order.size(); ++k) {
    const TerrainDraw& d = draws[order[k]];
    const terrain::TerrainMesh& m = *d.mesh;
    const MeshSize size = layout.sizes[k];
    const auto [firstVertex, firstIndex] = at[k];
    const bool valid = [&] {  // a layer the array does not have is a caller bug; draw uncoloured instead of faulting
      return d.imageryLayer < static_cast<int32_t>(layers_) && d.previousLayer < static_cast<int32_t>(layers_);
    }();
    assert(valid);
    const auto triangles = static_cast<uint32_t>(size.indices / 3);
    // The subtraction happens in double; only the small camera-relative offset becomes float.
    PreparedDraw p;
    p.push = TerrainPush{glm::vec4(glm::vec3(m.origin - cameraPosition), 0.0f), d.imageryUv, d.previousUv,
                         glm::vec4(valid ? static_cast<float>(d.imageryLayer) : -1.0f,
                                   valid ? static_cast<float>(d.previousLayer) : -1.0f, d.imageryBlend, 0.0f),
                         glm::uvec4(firstIndex / 3, 0u, 0u, 0u)};
    p.indexCount = static_cast<uint32_t>(size.indices);
    p.firstIndex = firstIndex;
    p.vertexOffset = static_cast<int32_t>(firstVertex);
    pdst[list.size()] = TerrainPiece{p.push.originFromCamera, p.push.imageryUv, p.push.previousUv, p.push.layers,
                                     glm::uvec4(firstIndex / 3, firstVertex, triangles, 0u)};
    list.push_back(p);
  }
  const VkBufferCopy vcopy{0, 0, VkDeviceSize{layout.vertices} * sizeof(terrain::TerrainVertex)};
  const VkBufferCopy icopy{0, 0, VkDeviceSize{layout.indices} * sizeof(uint32_t)};
  vkCmdCopyBuffer(cmd, vertices_[s].get(), deviceVertices_[s].get(), 1, &vcopy);
  vkCmdCopyBuffer(cmd, indices_[s].get(), deviceIndices_[s].get(), 1, &icopy);
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                VK_PIPELINE_STAGE_2_VERTEX_ATTRIBUTE_INPUT_BIT | VK_PIPELINE_STAGE_2_INDEX_INPUT_BIT |
                    VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT | VK_ACCESS_2_INDEX_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
  return layout.indices / 3;
}

void TerrainPass::recordDraws(VkCommandBuffer cmd, int slot, VkDescriptorSet frameSet, VkPipeline pipeline) const {
  const auto s = static_cast<size_t>(slot);
  if (prepared_[s].empty()) return;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
  const VkDescriptorSet sets[] = {frameSet, imagerySet_, detail_.set()};
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_.get(), 0, 3, sets, 0, nullptr);
  const VkBuffer vb = deviceVertices_[s].get();
  const VkDeviceSize zero = 0;
  vkCmdBindVertexBuffers(cmd, 0, 1, &vb, &zero);
  vkCmdBindIndexBuffer(cmd, deviceIndices_[s].get(), 0, VK_INDEX_TYPE_UINT32);
  for (const PreparedDraw& d : prepared_[s]) {
    vkCmdPushConstants(cmd, layout_.get(), kPushStages, 0, sizeof(d.push), &d.push);
    vkCmdDrawIndexed(cmd, d.indexCount, 1, d.firstIndex, d.vertexOffset, 0);
  }
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
  return {deviceVertices_[s].get(), deviceIndices_[s].get(), pieces_[s].get(),
          static_cast<uint32_t>(prepared_[s].size())};
}

uint64_t TerrainPass::gpuBytes() const {
  uint64_t bytes = imagery_.bytes + companionArray_.bytes + detail_.gpuBytes();
  for (size_t s = 0; s < kSlots; ++s)
    bytes += vertices_[s].size() + indices_[s].size() + staging_[s].size() + pieces_[s].size() +
             deviceVertices_[s].size() + deviceIndices_[s].size();
  return bytes;
}

}  // namespace vegstream::render
