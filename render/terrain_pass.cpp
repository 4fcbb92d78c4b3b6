#include "render/terrain_pass.h"

#include <cassert>
#include <cstddef>
#include <cstring>
#include <string>

#include <glm/vec4.hpp>

#include "render/descriptors.h"
#include "render/pipeline_builder.h"
#include "render/render_targets.h"
#include "render/vk_check.h"
#include "shaders/terrain.frag.h"
#include "shaders/terrain.vert.h"

namespace vegstream::render {
namespace {
struct TerrainPush {  // shaders/common/terrain_push.glsl
  glm::vec4 originFromCamera;
  glm::vec4 imageryUv;
  glm::vec4 previousUv;
  glm::vec4 layers;
};
static_assert(sizeof(TerrainPush) == 64 && sizeof(TerrainPush) <= 128, "Vulkan guarantees 128 bytes of push constants");
static_assert(sizeof(terrain::TerrainVertex) == 36, "must match the attributes of shaders/terrain.vert");
constexpr VkShaderStageFlags kPushStages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
constexpr VkDeviceSize kTileBytes = VkDeviceSize{kImageryTileSize} * kImageryTileSize * 4;

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

}  // namespace

TerrainPass::TerrainPass(const Context& ctx, VkDescriptorSetLayout frameLayout, VkSampleCountFlagBits samples)
    : ctx_(&ctx), detail_(ctx, vegetation::defaultTerrainTypes()) {
  imageryLayout_ = createSingleBindingLayout(ctx, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                                             VK_SHADER_STAGE_FRAGMENT_BIT, "terrain imagery layout");
  imageryPool_ = createSingleBindingPool(ctx, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, "terrain imagery pool");
  imagerySet_ = allocateDescriptorSet(ctx, imageryPool_.get(), imageryLayout_.get(), "terrain imagery set");
  sampler_ = createLinearClampSampler(ctx, "terrain imagery sampler");

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

  // One layer until the scene says how many it streams, so the descriptor is always valid.
  setImageryLayers(1, [](GpuImage&&) {});
}

void TerrainPass::setImageryLayers(uint32_t layers, const RetireImage& retire) {
  assert(layers >= 1);
  if (imagery_.image) retire(std::move(imagery_));
  imagery_ = createImageArray(*ctx_, {kImageryTileSize, kImageryTileSize}, layers, VK_FORMAT_R8G8B8A8_SRGB,
                              VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, "terrain imagery array", 1,
                              VK_FORMAT_R8G8B8A8_UNORM);
  layers_ = layers;
  // Every layer starts shader-readable (never sampled before its upload: the streamer hands out
  // a layer only with its tile), so uploads can move one layer at a time.
  ctx_->submitAndWait([&](VkCommandBuffer cmd) {
    transitionImageRange(cmd, imagery_.get(), {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, layers}, VK_IMAGE_LAYOUT_UNDEFINED,
                         VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, 0,
                         VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                         VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  });
  // The caller guarantees no frame in flight uses the set (the renderer waits for idle first).
  writeSampledImage(*ctx_, imagerySet_, sampler_.get(), imagery_.view.get());
}

void TerrainPass::ensureCapacity(GpuBuffer& buffer, VkDeviceSize bytes, VkBufferUsageFlags usage, const char* what,
                                 int slot, const RetireBuffer& retire) {
  if (buffer.buffer && buffer.size >= bytes) return;
  if (buffer.buffer) retire(std::move(buffer));
  buffer = createBuffer(*ctx_, grownSize(bytes, 256 * 1024), usage, MemoryUse::HostUpload,
                        std::string("terrain ") + what + " (slot " + std::to_string(slot) + ")");
}

void TerrainPass::recordUploads(VkCommandBuffer cmd, int slot, std::span<const ImageryUpload> uploads,
                                const RetireBuffer& retire) {
  if (uploads.empty()) return;
  const auto s = static_cast<size_t>(slot);
  ensureCapacity(staging_[s], kTileBytes * uploads.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, "imagery staging", slot,
                 retire);
  VkDeviceSize offset = 0;
  for (const ImageryUpload& u : uploads) {
    assert(u.rgba != nullptr && u.layer < layers_ && "the streamer's slots fit the array it sized");
    std::memcpy(static_cast<uint8_t*>(staging_[s].mapped) + offset, u.rgba, kTileBytes);
    recordImageUpload(cmd, staging_[s], imagery_, u.layer, offset);
    offset += kTileBytes;
  }
}

uint64_t TerrainPass::record(VkCommandBuffer cmd, int slot, VkDescriptorSet frameSet, const glm::dvec3& cameraPosition,
                             std::span<const TerrainDraw> draws, const RetireBuffer& retire) {
  const auto s = static_cast<size_t>(slot);
  VkDeviceSize vertexBytes = 0, indexBytes = 0;
  for (const TerrainDraw& d : draws) {
    if (!d.mesh || d.mesh->empty()) continue;
    const MeshSize size = flatSize(*d.mesh);
    vertexBytes += size.vertices * sizeof(terrain::TerrainVertex);
    indexBytes += size.indices * sizeof(uint32_t);
  }
  if (indexBytes == 0) return 0;
  ensureCapacity(vertices_[s], vertexBytes, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, "vertices", slot, retire);
  ensureCapacity(indices_[s], indexBytes, VK_BUFFER_USAGE_INDEX_BUFFER_BIT, "indices", slot, retire);

  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_.get());
  const VkDescriptorSet sets[] = {frameSet, imagerySet_, detail_.set()};
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_.get(), 0, 3, sets, 0, nullptr);
  const VkBuffer vb = vertices_[s].get();
  const VkDeviceSize zero = 0;
  vkCmdBindVertexBuffers(cmd, 0, 1, &vb, &zero);
  vkCmdBindIndexBuffer(cmd, indices_[s].get(), 0, VK_INDEX_TYPE_UINT32);

  auto* vdst = static_cast<uint8_t*>(vertices_[s].mapped);
  auto* idst = static_cast<uint8_t*>(indices_[s].mapped);
  uint32_t firstVertex = 0, firstIndex = 0;
  uint64_t triangles = 0;
  for (const TerrainDraw& d : draws) {
    if (!d.mesh || d.mesh->empty()) continue;
    const terrain::TerrainMesh& m = *d.mesh;
    const MeshSize size = flatSize(m);
    if (size.indices == 0) continue;
    copyFlat(m, reinterpret_cast<terrain::TerrainVertex*>(vdst) + firstVertex,
             reinterpret_cast<uint32_t*>(idst) + firstIndex);
    const bool valid = [&] {  // a layer the array does not have is a caller bug; draw uncoloured instead of faulting
      return d.imageryLayer < static_cast<int32_t>(layers_) && d.previousLayer < static_cast<int32_t>(layers_);
    }();
    assert(valid);
    // The subtraction happens in double; only the small camera-relative offset becomes float.
    const TerrainPush push{glm::vec4(glm::vec3(m.origin - cameraPosition), 0.0f), d.imageryUv, d.previousUv,
                           glm::vec4(valid ? static_cast<float>(d.imageryLayer) : -1.0f,
                                     valid ? static_cast<float>(d.previousLayer) : -1.0f, d.imageryBlend, 0.0f)};
    vkCmdPushConstants(cmd, layout_.get(), kPushStages, 0, sizeof(push), &push);
    vkCmdDrawIndexed(cmd, static_cast<uint32_t>(size.indices), 1, firstIndex, static_cast<int32_t>(firstVertex), 0);
    firstVertex += static_cast<uint32_t>(size.vertices);
    firstIndex += static_cast<uint32_t>(size.indices);
    triangles += size.indices / 3;
  }
  return triangles;
}

uint64_t TerrainPass::gpuBytes() const {
  uint64_t bytes = imagery_.bytes + detail_.gpuBytes();
  for (size_t s = 0; s < kSlots; ++s) bytes += vertices_[s].size + indices_[s].size + staging_[s].size;
  return bytes;
}

}  // namespace vegstream::render
