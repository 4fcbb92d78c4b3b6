#include "render/terrain_pass.h"

#include <cstddef>

#include <glm/vec4.hpp>

#include "render/pipeline_builder.h"
#include "render/render_targets.h"
#include "shaders/terrain.frag.h"
#include "shaders/terrain.vert.h"

namespace vegstream::render {
namespace {
struct TerrainPush {
  glm::vec4 originFromCamera;
};
static_assert(sizeof(terrain::TerrainVertex) == 28, "must match the attributes of shaders/terrain.vert");
}  // namespace

TerrainPass::TerrainPass(const Context& ctx, VkDescriptorSetLayout frameLayout, VkSampleCountFlagBits samples)
    : ctx_(&ctx) {
  const VkPushConstantRange push{VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(TerrainPush)};
  layout_ = createPipelineLayout(ctx, {&frameLayout, 1}, {&push, 1}, "terrain pipeline layout");
  GraphicsPipelineDesc desc;
  desc.name = "terrain pipeline";
  desc.stages = {{VK_SHADER_STAGE_VERTEX_BIT, spv_terrain_vert}, {VK_SHADER_STAGE_FRAGMENT_BIT, spv_terrain_frag}};
  desc.bindings = {{0, sizeof(terrain::TerrainVertex), VK_VERTEX_INPUT_RATE_VERTEX}};
  desc.attributes = {
      {0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(terrain::TerrainVertex, position)},
      {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(terrain::TerrainVertex, normal)},
      {2, 0, VK_FORMAT_R32_SFLOAT, offsetof(terrain::TerrainVertex, heightMsl)},
  };
  desc.samples = samples;
  desc.colorFormat = kColorFormat;
  desc.depthFormat = kDepthFormat;
  desc.layout = layout_.get();
  pipeline_ = createGraphicsPipeline(ctx, desc);
}

void TerrainPass::setMesh(const terrain::TerrainMesh& mesh, const std::function<void(GpuBuffer&&)>& retire) {
  if (vertices_.buffer) retire(std::move(vertices_));
  if (indices_.buffer) retire(std::move(indices_));
  vertices_ = {};
  indices_ = {};
  indexCount_ = 0;
  origin_ = mesh.origin;
  if (mesh.indices.empty()) return;
  vertices_ = createBufferWithData(*ctx_, mesh.vertices.data(), mesh.vertices.size() * sizeof(terrain::TerrainVertex),
                                   VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, "terrain vertices");
  indices_ = createBufferWithData(*ctx_, mesh.indices.data(), mesh.indices.size() * sizeof(uint32_t),
                                  VK_BUFFER_USAGE_INDEX_BUFFER_BIT, "terrain indices");
  indexCount_ = static_cast<uint32_t>(mesh.indices.size());
}

uint64_t TerrainPass::record(VkCommandBuffer cmd, VkDescriptorSet frameSet, const glm::dvec3& cameraPosition) const {
  if (indexCount_ == 0) return 0;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_.get());
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_.get(), 0, 1, &frameSet, 0, nullptr);
  // The subtraction happens in double; only the small camera-relative offset becomes float.
  const TerrainPush push{glm::vec4(glm::vec3(origin_ - cameraPosition), 0.0f)};
  vkCmdPushConstants(cmd, layout_.get(), VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(push), &push);
  const VkBuffer vb = vertices_.get();
  const VkDeviceSize offset = 0;
  vkCmdBindVertexBuffers(cmd, 0, 1, &vb, &offset);
  vkCmdBindIndexBuffer(cmd, indices_.get(), 0, VK_INDEX_TYPE_UINT32);
  vkCmdDrawIndexed(cmd, indexCount_, 1, 0, 0, 0);
  return indexCount_ / 3;
}

}  // namespace vegstream::render
