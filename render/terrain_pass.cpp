#include "render/terrain_pass.h"

#include <cstddef>
#include <cstring>

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
  glm::vec4 flags;
};
static_assert(sizeof(TerrainPush) == 32);
static_assert(sizeof(terrain::TerrainVertex) == 36, "must match the attributes of shaders/terrain.vert");
constexpr VkShaderStageFlags kPushStages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
}  // namespace

TerrainPass::TerrainPass(const Context& ctx, VkDescriptorSetLayout frameLayout, VkSampleCountFlagBits samples)
    : ctx_(&ctx) {
  imageryLayout_ = createSingleBindingLayout(ctx, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                                             VK_SHADER_STAGE_FRAGMENT_BIT, "terrain imagery layout");
  imageryPool_ = createSingleBindingPool(ctx, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, "terrain imagery pool");
  imagerySet_ = allocateDescriptorSet(ctx, imageryPool_.get(), imageryLayout_.get(), "terrain imagery set");
  sampler_ = createLinearClampSampler(ctx, "terrain imagery sampler");
  const VkDescriptorSetLayout setLayout = imageryLayout_.get();

  const VkPushConstantRange push{kPushStages, 0, sizeof(TerrainPush)};
  const VkDescriptorSetLayout sets[] = {frameLayout, setLayout};
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

  // A 1 × 1 transparent texture until imagery arrives, so the set is always valid.
  uploadImagery(ColorImage{1, 1, {0, 0, 0, 0}});
  hasImagery_ = false;
}

void TerrainPass::uploadImagery(const ColorImage& image) {
  imagery_ = createImage2D(*ctx_, {image.width, image.height}, VK_FORMAT_R8G8B8A8_SRGB,
                           VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, VK_SAMPLE_COUNT_1_BIT,
                           "terrain imagery");
  GpuBuffer staging = createBuffer(*ctx_, image.rgba.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::HostUpload,
                                   "terrain imagery staging");
  std::memcpy(staging.mapped, image.rgba.data(), image.rgba.size());
  ctx_->submitAndWait([&](VkCommandBuffer cmd) { recordImageUpload(cmd, staging, imagery_); });
  hasImagery_ = true;
  writeImageryDescriptor();
}

void TerrainPass::writeImageryDescriptor() {
  writeSampledImage(*ctx_, imagerySet_, sampler_.get(), imagery_.view.get());
}

void TerrainPass::setMesh(const terrain::TerrainMesh& mesh, const ColorImage* imagery, const Retire& retire) {
  // The descriptor set is rewritten below while earlier frames may still read it: wait for them
  // (meshes change when a flight opens, not every frame).
  vkCheck(vkDeviceWaitIdle(ctx_->device()), "vkDeviceWaitIdle");
  retire(std::move(vertices_), GpuImage{});
  retire(std::move(indices_), std::move(imagery_));
  vertices_ = {};
  indices_ = {};
  indexCount_ = 0;
  origin_ = mesh.origin;
  uploadImagery(imagery && imagery->width > 0 ? *imagery : ColorImage{1, 1, {0, 0, 0, 0}});
  hasImagery_ = imagery && imagery->width > 0;
  gpuBytes_ = hasImagery_ ? imagery->rgba.size() : 0;
  if (mesh.indices.empty()) return;
  vertices_ = createBufferWithData(*ctx_, mesh.vertices.data(), mesh.vertices.size() * sizeof(terrain::TerrainVertex),
                                   VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, "terrain vertices");
  indices_ = createBufferWithData(*ctx_, mesh.indices.data(), mesh.indices.size() * sizeof(uint32_t),
                                  VK_BUFFER_USAGE_INDEX_BUFFER_BIT, "terrain indices");
  indexCount_ = static_cast<uint32_t>(mesh.indices.size());
  gpuBytes_ += vertices_.size + indices_.size;
}

uint64_t TerrainPass::record(VkCommandBuffer cmd, VkDescriptorSet frameSet, const glm::dvec3& cameraPosition) const {
  if (indexCount_ == 0) return 0;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_.get());
  const VkDescriptorSet sets[] = {frameSet, imagerySet_};
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_.get(), 0, 2, sets, 0, nullptr);
  // The subtraction happens in double; only the small camera-relative offset becomes float.
  const TerrainPush push{glm::vec4(glm::vec3(origin_ - cameraPosition), 0.0f),
                         glm::vec4(hasImagery_ ? 1.0f : 0.0f, 0.0f, 0.0f, 0.0f)};
  vkCmdPushConstants(cmd, layout_.get(), kPushStages, 0, sizeof(push), &push);
  const VkBuffer vb = vertices_.get();
  const VkDeviceSize offset = 0;
  vkCmdBindVertexBuffers(cmd, 0, 1, &vb, &offset);
  vkCmdBindIndexBuffer(cmd, indices_.get(), 0, VK_INDEX_TYPE_UINT32);
  vkCmdDrawIndexed(cmd, indexCount_, 1, 0, 0, 0);
  return indexCount_ / 3;
}

}  // namespace vegstream::render
