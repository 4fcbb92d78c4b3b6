#include "render/sky_pass.h"

#include "render/pipeline_builder.h"
#include "render/render_targets.h"
#include "shaders/sky.frag.h"
#include "shaders/sky.vert.h"

namespace vegstream::render {

SkyPass::SkyPass(const Context& ctx, VkDescriptorSetLayout frameLayout, VkSampleCountFlagBits samples) {
  layout_ = createPipelineLayout(ctx, {&frameLayout, 1}, {}, "sky pipeline layout");
  GraphicsPipelineDesc desc;
  desc.name = "sky pipeline";
  desc.stages = {{VK_SHADER_STAGE_VERTEX_BIT, spv_sky_vert}, {VK_SHADER_STAGE_FRAGMENT_BIT, spv_sky_frag}};
  desc.cullMode = VK_CULL_MODE_NONE;
  desc.depthTest = false;  // drawn first, behind everything
  desc.depthWrite = false;
  desc.samples = samples;
  desc.colorFormat = kColorFormat;
  desc.depthFormat = kDepthFormat;
  desc.layout = layout_.get();
  pipeline_ = createGraphicsPipeline(ctx, desc);
}

void SkyPass::record(VkCommandBuffer cmd, VkDescriptorSet frameSet) const {
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_.get());
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_.get(), 0, 1, &frameSet, 0, nullptr);
  vkCmdDraw(cmd, 3, 1, 0, 0);
}

}  // namespace vegstream::render
