#include "render/render_targets.h"

#include <vector>

namespace vegstream::render {

RenderTargets::RenderTargets(const Context& ctx, VkExtent2D extent, VkSampleCountFlagBits samples)
    : extent_(extent), samples_(samples) {
  const VkImageUsageFlags readable = VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
  color_ = createImage2D(ctx, extent, kColorFormat, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | readable,
                         VK_SAMPLE_COUNT_1_BIT, "colour target");
  depth_ = createImage2D(ctx, extent, kDepthFormat, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | readable,
                         VK_SAMPLE_COUNT_1_BIT, "depth target");
  if (multisampled()) {
    colorMsaa_ =
        createImage2D(ctx, extent, kColorFormat, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, samples, "colour target (MSAA)");
    // Sampled: the Hi-Z build reads every sample (hiz_pass.h).
    depthMsaa_ = createImage2D(ctx, extent, kDepthFormat,
                               VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, samples,
                               "depth target (MSAA)");
  }
}

void RenderTargets::beginRendering(VkCommandBuffer cmd, Load load, bool resolve) const {
  const auto colorStage = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
  const auto depthStage = VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
  const auto depthAccess =
      VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  if (load == Load::Clear) {
    // Attachments start undefined each frame: everything is cleared.
    std::vector<const GpuImage*> colorImages{&color()}, depthImages{&depth()};
    if (multisampled()) {
      colorImages.push_back(&colorAttachment());
      depthImages.push_back(&depthAttachment());
    }
    for (const GpuImage* img : colorImages)
      transitionImage(cmd, img->get(), img->aspect, VK_IMAGE_LAYOUT_UNDEFINED,
                      VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0, colorStage,
                      VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
    for (const GpuImage* img : depthImages)
      transitionImage(cmd, img->get(), img->aspect, VK_IMAGE_LAYOUT_UNDEFINED,
                      VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0, depthStage,
                      depthAccess);
  } else {
    // The previous scope's attachment writes (and its resolve, if any) before this one's
    // loads, draws and resolve writes.
    memoryBarrier(cmd, colorStage | depthStage,
                  VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                  colorStage | depthStage,
                  VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | depthAccess);
  }
  const VkAttachmentLoadOp loadOp = load == Load::Clear ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;

  VkRenderingAttachmentInfo colorInfo{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  colorInfo.imageView = colorAttachment().view.get();
  colorInfo.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  colorInfo.loadOp = loadOp;
  colorInfo.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  colorInfo.clearValue.color = {{0.0f, 0.0f, 0.0f, 1.0f}};
  VkRenderingAttachmentInfo depthInfo{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  depthInfo.imageView = depthAttachment().view.get();
  depthInfo.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
  depthInfo.loadOp = loadOp;
  depthInfo.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  depthInfo.clearValue.depthStencil = {0.0f, 0};  // reverse-Z: 0 is the far plane
  if (multisampled() && resolve) {  // else the MSAA attachments are stored for the next scope
    colorInfo.resolveMode = VK_RESOLVE_MODE_AVERAGE_BIT;
    colorInfo.resolveImageView = color().view.get();
    colorInfo.resolveImageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    colorInfo.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    depthInfo.resolveMode = VK_RESOLVE_MODE_SAMPLE_ZERO_BIT;  // required of every device
    depthInfo.resolveImageView = depth().view.get();
    depthInfo.resolveImageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    depthInfo.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  }
  VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
  ri.renderArea = {{0, 0}, extent_};
  ri.layerCount = 1;
  ri.colorAttachmentCount = 1;
  ri.pColorAttachments = &colorInfo;
  ri.pDepthAttachment = &depthInfo;
  vkCmdBeginRendering(cmd, &ri);
  // Flip nothing here: the projection matrix already flips y for Vulkan.
  const VkViewport viewport{0.0f, 0.0f, static_cast<float>(extent_.width), static_cast<float>(extent_.height),
                            0.0f, 1.0f};
  const VkRect2D scissor{{0, 0}, extent_};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &scissor);
}

}  // namespace vegstream::render
