// The sun's cascaded shadow map (sun_shadow_pass.h).
#include "render/sun_shadow_pass.h"

#include <string>

#include "render/descriptors.h"
#include "render/vk_check.h"

namespace vegstream::render {
namespace {

constexpr VkFormat kShadowFormat = VK_FORMAT_D32_SFLOAT;
constexpr VkPipelineStageFlags2 kReaders =
    VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT |
    VK_PIPELINE_STAGE_2_GEOMETRY_SHADER_BIT | VK_PIPELINE_STAGE_2_TESSELLATION_EVALUATION_SHADER_BIT;

}  // namespace

SunShadowPass::SunShadowPass(const Context& ctx, uint32_t mapSize) : ctx_(&ctx), size_(mapSize) {
  map_ = createImageArray(
      ctx, {mapSize, mapSize}, kShadowCascades, kShadowFormat,
      VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
      "sun shadow map");
  placeholder_ =
      createImageArray(ctx, {1, 1}, kShadowCascades, kShadowFormat,
                       VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, "sun shadow placeholder");
  for (int c = 0; c < kShadowCascades; ++c) {
    VkImageViewCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    ci.image = map_.get();
    ci.viewType = VK_IMAGE_VIEW_TYPE_2D;
    ci.format = kShadowFormat;
    ci.subresourceRange = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, static_cast<uint32_t>(c), 1};
    VkImageView view = VK_NULL_HANDLE;
    vkCheck(vkCreateImageView(ctx.device(), &ci, nullptr, &view), "vkCreateImageView(shadow cascade)");
    ctx.setName(VK_OBJECT_TYPE_IMAGE_VIEW, view, "sun shadow cascade " + std::to_string(c));
    layers_[size_t(c)] = ImageView(ctx.device(), view);
  }
  VkSamplerCreateInfo si{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  si.magFilter = si.minFilter = VK_FILTER_LINEAR;
  si.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  si.addressModeU = si.addressModeV = si.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  si.compareEnable = VK_TRUE;
  si.compareOp = VK_COMPARE_OP_GREATER_OR_EQUAL;  // reverse-Z: lit when at least as near the sun
  si.maxLod = 0.0f;
  VkSampler sampler = VK_NULL_HANDLE;
  vkCheck(vkCreateSampler(ctx.device(), &si, nullptr, &sampler), "vkCreateSampler(shadow)");
  ctx.setName(VK_OBJECT_TYPE_SAMPLER, sampler, "sun shadow sampler");
  sampler_ = Sampler(ctx.device(), sampler);
  // Cleared to the far plane: nothing casts until a frame draws casters.
  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    const VkImageSubresourceRange all{VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, 0, kShadowCascades};
    for (const GpuImage* img : {&map_, &placeholder_}) {
      transitionImageRange(cmd, img->get(), all, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                           VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
      const VkClearDepthStencilValue clear{0.0f, 0};
      vkCmdClearDepthStencilImage(cmd, img->get(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &clear, 1, &all);
      transitionImageRange(cmd, img->get(), all, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                           VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_CLEAR_BIT,
                           VK_ACCESS_2_TRANSFER_WRITE_BIT, kReaders, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    }
  });
}

void SunShadowPass::writeFrameSet(VkDescriptorSet frameSet, bool placeholder) const {
  writeSampledImage(*ctx_, frameSet, sampler_.get(), (placeholder ? placeholder_ : map_).view.get(), 4);
}

void SunShadowPass::record(VkCommandBuffer cmd, const ShadowCascades& cascades, const DrawCasters& draw) const {
  const VkImageSubresourceRange all{VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, 0, kShadowCascades};
  // Earlier frames' reads finish before the map is drawn again.
  transitionImageRange(cmd, map_.get(), all, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                       VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, kReaders, 0,
                       VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                       VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
  for (int c = 0; c < kShadowCascades; ++c) {
    if ((cascades.drawn & (1u << c)) == 0) continue;  // kept: its layout changes back and forth, its contents stay
    VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth.imageView = layers_[size_t(c)].get();
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    depth.clearValue.depthStencil = {0.0f, 0};
    VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
    ri.renderArea = {{0, 0}, {size_, size_}};
    ri.layerCount = 1;
    ri.pDepthAttachment = &depth;
    vkCmdBeginRendering(cmd, &ri);
    const VkViewport vp{0.0f, 0.0f, static_cast<float>(size_), static_cast<float>(size_), 0.0f, 1.0f};
    const VkRect2D scissor{{0, 0}, {size_, size_}};
    vkCmdSetViewport(cmd, 0, 1, &vp);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
    draw(cmd, c, cascades.matrices[size_t(c)]);
    vkCmdEndRendering(cmd);
  }
  transitionImageRange(cmd, map_.get(), all, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                       VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                       VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, kReaders, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
}

}  // namespace vegstream::render
