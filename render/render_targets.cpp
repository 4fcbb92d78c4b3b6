#include "render/render_targets.h"

#include <cassert>
#include <vector>

namespace vegstream::render {
namespace {
constexpr VkPipelineStageFlags2 kColorStage = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
constexpr VkAccessFlags2 kColorAccess = VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT;
constexpr VkPipelineStageFlags2 kDepthStage =
    VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
constexpr VkAccessFlags2 kDepthAccess =
    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;

// Starts a frame's use of an image: its old contents are discarded.
void discardInto(VkCommandBuffer cmd, const GpuImage& img, VkImageLayout layout, VkPipelineStageFlags2 stage,
                 VkAccessFlags2 access) {
  transitionImage(cmd, img.get(), img.aspect, VK_IMAGE_LAYOUT_UNDEFINED, layout, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                  0, stage, access);
}

VkRenderingAttachmentInfo attachment(const GpuImage& img, VkImageLayout layout, VkAttachmentLoadOp load) {
  VkRenderingAttachmentInfo info{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  info.imageView = img.view.get();
  info.imageLayout = layout;
  info.loadOp = load;
  info.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  return info;
}
}  // namespace

RenderTargets::RenderTargets(const Context& ctx, VkExtent2D extent, VkSampleCountFlagBits samples, bool deferredTerrain,
                             bool computeRaster)
    : extent_(extent), samples_(samples), deferredTerrain_(deferredTerrain) {
  const VkImageUsageFlags readable = VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
  // The deferred terrain's shade stores into the colour attachment; the tone map reads the
  // resolved colour as a storage image.
  const VkImageUsageFlags storage = deferredTerrain ? VK_IMAGE_USAGE_STORAGE_BIT : 0;
  color_ = createImage2D(ctx, extent, kColorFormat,
                         VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | readable | VK_IMAGE_USAGE_STORAGE_BIT,
                         VK_SAMPLE_COUNT_1_BIT, "colour target (HDR)");
  display_ = createImage2D(ctx, extent, kDisplayFormat,
                           VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | readable | VK_IMAGE_USAGE_STORAGE_BIT,
                           VK_SAMPLE_COUNT_1_BIT, "display target", kDisplayStorageFormat);
  depth_ = createImage2D(ctx, extent, kDepthFormat, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | readable,
                         VK_SAMPLE_COUNT_1_BIT, "depth target");
  if (multisampled()) {
    colorMsaa_ = createImage2D(ctx, extent, kColorFormat, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | storage, samples,
                               "colour target (MSAA, HDR)");
    // Sampled: the Hi-Z build reads every sample (hiz_pass.h).
    depthMsaa_ = createImage2D(ctx, extent, kDepthFormat,
                               VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, samples,
                               "depth target (MSAA)");
  }
  if (deferredTerrain && !computeRaster)
    visibility_ = createImage2D(ctx, extent, kVisibilityFormat,
                                VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, samples,
                                "terrain visibility target");
}

void RenderTargets::beginScope(VkCommandBuffer cmd, const VkRenderingAttachmentInfo& color,
                               const VkRenderingAttachmentInfo& depth) const {
  VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
  ri.renderArea = {{0, 0}, extent_};
  ri.layerCount = 1;
  ri.colorAttachmentCount = 1;
  ri.pColorAttachments = &color;
  ri.pDepthAttachment = &depth;
  vkCmdBeginRendering(cmd, &ri);
  setViewport(cmd);
}

void RenderTargets::setViewport(VkCommandBuffer cmd) const {
  // Flip nothing here: the projection matrix already flips y for Vulkan.
  const VkViewport viewport{0.0f, 0.0f, static_cast<float>(extent_.width), static_cast<float>(extent_.height),
                            0.0f, 1.0f};
  const VkRect2D scissor{{0, 0}, extent_};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &scissor);
}

void RenderTargets::beginRendering(VkCommandBuffer cmd, Load load, bool resolve, bool resolveDepth) const {
  assert(load != Load::Shaded || deferredTerrain());
  if (load == Load::Clear) {  // attachments and resolve targets start undefined each frame
    discardInto(cmd, color(), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, kColorStage, kColorAccess);
    discardInto(cmd, depth(), VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, kDepthStage, kDepthAccess);
    if (multisampled()) {
      discardInto(cmd, colorAttachment(), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, kColorStage, kColorAccess);
      discardInto(cmd, depthAttachment(), VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, kDepthStage, kDepthAccess);
    }
  } else if (load == Load::Keep) {
    // The previous scope's attachment writes (and its resolve, if any) before this one's loads,
    // draws and resolve writes.
    memoryBarrier(cmd, kColorStage | kDepthStage,
                  VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                  kColorStage | kDepthStage, kColorAccess | kDepthAccess);
  } else {  // Shaded: the shade's stores, then the visibility scope's depth, become the attachments'
    if (multisampled()) {  // the resolve targets have not been touched this frame
      discardInto(cmd, color(), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, kColorStage, kColorAccess);
      discardInto(cmd, depth(), VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, kDepthStage, kDepthAccess);
    }
    transitionImage(cmd, colorAttachment().get(), colorAttachment().aspect, VK_IMAGE_LAYOUT_GENERAL,
                    VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                    VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, kColorStage, kColorAccess);
    // The depth from beginVisibility's scope, or (the terrain rasterised in compute) beginTerrainDepth's.
    memoryBarrier(cmd, kDepthStage, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, kDepthStage, kDepthAccess);
  }

  const VkAttachmentLoadOp op = load == Load::Clear ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
  VkRenderingAttachmentInfo colorInfo = attachment(colorAttachment(), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, op);
  colorInfo.clearValue.color = {{0.0f, 0.0f, 0.0f, 1.0f}};
  VkRenderingAttachmentInfo depthInfo = attachment(depthAttachment(), VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, op);
  depthInfo.clearValue.depthStencil = {0.0f, 0};  // reverse-Z: 0 is the far plane
  if (multisampled() && resolve) {  // else the MSAA attachments are stored for the next scope
    colorInfo.resolveMode = VK_RESOLVE_MODE_AVERAGE_BIT;
    colorInfo.resolveImageView = color().view.get();
    colorInfo.resolveImageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    colorInfo.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    if (resolveDepth) {
      depthInfo.resolveMode = VK_RESOLVE_MODE_SAMPLE_ZERO_BIT;  // required of every device
      depthInfo.resolveImageView = depth().view.get();
      depthInfo.resolveImageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    }
    depthInfo.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  }
  beginScope(cmd, colorInfo, depthInfo);
}

void RenderTargets::beginVisibility(VkCommandBuffer cmd) const {
  assert(deferredTerrain());
  discardInto(cmd, visibility_, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, kColorStage, kColorAccess);
  discardInto(cmd, depthAttachment(), VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, kDepthStage, kDepthAccess);
  VkRenderingAttachmentInfo idInfo =
      attachment(visibility_, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_ATTACHMENT_LOAD_OP_DONT_CARE);
  // Not cleared: where the depth stays at the far plane's 0 the shade reads sky (on the H200 a
  // multisampled clear costs a full-screen write, 0.6 ms at 1080p × 4).
  VkRenderingAttachmentInfo depthInfo =
      attachment(depthAttachment(), VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_ATTACHMENT_LOAD_OP_CLEAR);
  depthInfo.clearValue.depthStencil = {0.0f, 0};
  beginScope(cmd, idInfo, depthInfo);
}

void RenderTargets::beginTerrainDepth(VkCommandBuffer cmd, std::optional<float> clearDepth) const {
  assert(computeRaster());
  discardInto(cmd, depthAttachment(), VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, kDepthStage, kDepthAccess);
  VkRenderingAttachmentInfo depthInfo =
      attachment(depthAttachment(), VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                 clearDepth ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_DONT_CARE);
  depthInfo.clearValue.depthStencil = {clearDepth.value_or(0.0f), 0};
  VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
  ri.renderArea = {{0, 0}, extent_};
  ri.layerCount = 1;
  ri.pDepthAttachment = &depthInfo;
  vkCmdBeginRendering(cmd, &ri);
  setViewport(cmd);
}

void RenderTargets::visibilityToShade(VkCommandBuffer cmd) const {
  transitionImage(cmd, visibility_.get(), visibility_.aspect, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                  VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, kColorStage, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  transitionImage(cmd, depthAttachment().get(), depthAttachment().aspect, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                  VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, kDepthStage,
                  VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                  VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  transitionImage(cmd, colorAttachment().get(), colorAttachment().aspect, VK_IMAGE_LAYOUT_UNDEFINED,
                  VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0,
                  VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
}

}  // namespace vegstream::render
