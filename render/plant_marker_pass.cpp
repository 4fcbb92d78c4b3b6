// Classification markers (plant_marker_pass.h).
#include "render/plant_marker_pass.h"

#include <string>

#include "render/descriptors.h"
#include "render/pipeline_builder.h"
#include "render/render_targets.h"
#include "shaders/plant_marker.frag.h"
#include "shaders/plant_marker.vert.h"

namespace vegstream::render {
namespace {
struct MarkerPush {
  uint32_t species, speciesCapacity;
};
}  // namespace

PlantMarkerPass::PlantMarkerPass(const Context& ctx, VkDescriptorSetLayout frameLayout, VkSampleCountFlagBits samples)
    : ctx_(&ctx) {
  const VkDescriptorSetLayoutBinding bindings[] = {
      {0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, VK_SHADER_STAGE_VERTEX_BIT, nullptr},
      {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_VERTEX_BIT, nullptr},
      {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_VERTEX_BIT, nullptr}};
  setLayout_ = createLayout(ctx, bindings, "plant marker set layout");
  const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, ClassifyPass::kSlots},
                                        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 2 * ClassifyPass::kSlots}};
  pool_ = createPool(ctx, sizes, ClassifyPass::kSlots, "plant marker pool");
  allocateSlotSets(ctx, pool_.get(), setLayout_.get(), sets_, "plant marker set");
  const VkPushConstantRange push{VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(MarkerPush)};
  const VkDescriptorSetLayout sets[] = {frameLayout, setLayout_.get()};
  layout_ = createPipelineLayout(ctx, sets, {&push, 1}, "plant marker pipeline layout");
  GraphicsPipelineDesc desc;
  desc.name = "plant marker pipeline";
  desc.stages = {{VK_SHADER_STAGE_VERTEX_BIT, spv_plant_marker_vert},
                 {VK_SHADER_STAGE_FRAGMENT_BIT, spv_plant_marker_frag}};
  desc.cullMode = VK_CULL_MODE_NONE;
  desc.samples = samples;
  desc.colorFormat = kColorFormat;
  desc.depthFormat = kDepthFormat;
  desc.layout = layout_.get();
  pipeline_ = createGraphicsPipeline(*ctx_, desc);
}

void PlantMarkerPass::record(VkCommandBuffer cmd, int slot, VkDescriptorSet frameSet, const ClassifyPass& classify,
                             uint32_t skipMask) {
  if (classify.speciesCount() == 0 || classify.triangles(slot) == VK_NULL_HANDLE) return;
  // The slot's previous frame has finished: its set may be rewritten (buffers may have grown).
  const VkDescriptorSet set = sets_[size_t(slot)];
  writeUniformBuffer(*ctx_, set, classify.species(), sizeof(SpeciesBlock), 0);
  writeStorageBuffer(*ctx_, set, classify.triangles(slot), 1);
  writeStorageBuffer(*ctx_, set, classify.records(slot), 2);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_.get());
  const VkDescriptorSet sets[] = {frameSet, set};
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_.get(), 0, 2, sets, 0, nullptr);
  for (uint32_t s = 0; s < classify.speciesCount(); ++s) {
    if ((skipMask >> s) & 1u) continue;
    const MarkerPush push{s, classify.clustersPerSpecies()};
    vkCmdPushConstants(cmd, layout_.get(), VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(push), &push);
    vkCmdDrawIndirect(cmd, classify.indirect(slot), VkDeviceSize{s} * sizeof(VkDrawIndirectCommand), 1,
                      sizeof(VkDrawIndirectCommand));
  }
}

}  // namespace vegstream::render
