#include "render/terrain_shade_pass.h"

#include <cassert>
#include <string>

#include <glm/vec4.hpp>

#include "render/descriptors.h"
#include "render/pipeline_builder.h"
#include "shaders/terrain_shade.comp.h"
#include "shaders/terrain_shade_ms.comp.h"

namespace vegstream::render {
namespace {
constexpr uint32_t kGroupSize = 8;  // local_size_x = local_size_y
}  // namespace

TerrainShadePass::TerrainShadePass(const Context& ctx, VkDescriptorSetLayout frameLayout, const TerrainPass& terrain,
                                   const RenderTargets& targets)
    : ctx_(&ctx) {
  assert(targets.deferredTerrain());
  const VkShaderStageFlags c = VK_SHADER_STAGE_COMPUTE_BIT;
  const VkDescriptorSetLayoutBinding bindings[] = {
      {0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, c, nullptr},  // visibility
      {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, c, nullptr},  // vertices
      {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, c, nullptr},  // indices
      {3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, c, nullptr},  // pieces
      {4, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, c, nullptr},   // colour target
      {5, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, c, nullptr},  // depth (0: no terrain)
  };
  inputsLayout_ = createLayout(ctx, bindings, "terrain shade inputs layout");
  const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 2 * kSlots},
                                        {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, kSlots},
                                        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 3 * kSlots}};
  pool_ = createPool(ctx, sizes, kSlots, "terrain shade pool");
  nearest_ = createNearestClampSampler(ctx, "terrain visibility sampler");
  for (int s = 0; s < kSlots; ++s) {
    inputs_[static_cast<size_t>(s)] = allocateDescriptorSet(ctx, pool_.get(), inputsLayout_.get(),
                                                            "terrain shade inputs (slot " + std::to_string(s) + ")");
    writeSampledImage(ctx, inputs_[static_cast<size_t>(s)], nearest_.get(), targets.visibility().view.get(), 0);
    writeSampledImage(ctx, inputs_[static_cast<size_t>(s)], nearest_.get(), targets.depthAttachment().view.get(), 5);
    writeStorageImage(ctx, inputs_[static_cast<size_t>(s)], targets.colorStorageView(), 4);
  }
  const VkPushConstantRange push{c, 0, sizeof(TerrainComputePush)};
  const VkDescriptorSetLayout sets[] = {frameLayout, terrain.imageryLayout(), terrain.detail().layout(),
                                        inputsLayout_.get()};
  layout_ = createPipelineLayout(ctx, sets, {&push, 1}, "terrain shade pipeline layout");
  pipeline_ = targets.multisampled()
                  ? createComputePipeline(ctx, layout_.get(), spv_terrain_shade_ms_comp, "terrain shade (MSAA)")
                  : createComputePipeline(ctx, layout_.get(), spv_terrain_shade_comp, "terrain shade");
}

void TerrainShadePass::record(VkCommandBuffer cmd, int slot, VkDescriptorSet frameSet, const TerrainPass& terrain,
                              const RenderTargets& targets) {
  const VkDescriptorSet inputs = inputs_[static_cast<size_t>(slot)];
  const TerrainGeometry g = terrain.geometry(slot);
  // The slot's buffers may have been reallocated since its last frame, which has completed (the
  // renderer waited for its fence), so the set is not in use. prepare() makes them exist even
  // without terrain (then every sample is sky and they are not read).
  assert(g.vertices && g.indices && g.pieces && "TerrainPass::prepare first");
  writeStorageBuffer(*ctx_, inputs, g.vertices, 1);
  writeStorageBuffer(*ctx_, inputs, g.indices, 2);
  writeStorageBuffer(*ctx_, inputs, g.pieces, 3);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_.get());
  const VkDescriptorSet sets[] = {frameSet, terrain.imagerySet(), terrain.detail().set(), inputs};
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.get(), 0, 4, sets, 0, nullptr);
  const TerrainComputePush push{glm::uvec4(g.pieceCount, 0u, 0u, 0u), glm::uvec4(0u)};
  vkCmdPushConstants(cmd, layout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
  const VkExtent2D e = targets.extent();
  vkCmdDispatch(cmd, (e.width + kGroupSize - 1) / kGroupSize, (e.height + kGroupSize - 1) / kGroupSize, 1);
  // The depth goes back to being an attachment (the Hi-Z build and the plants' scope expect it so).
  const GpuImage& depth = targets.depthAttachment();
  transitionImage(cmd, depth.get(), depth.aspect, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                  VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, 0,
                  VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT |
                      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                  VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
                      VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
}

}  // namespace vegstream::render
