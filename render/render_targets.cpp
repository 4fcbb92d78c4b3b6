#include "render/render_targets.h"

namespace vegstream::render {

RenderTargets::RenderTargets(const Context& ctx, VkExtent2D extent, VkSampleCountFlagBits samples)
    : extent_(extent), samples_(samples) {
  const VkImageUsageFlags readable = VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
  color_ = createImage2D(ctx, extent, kColorFormat, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | readable,
                         VK_SAMPLE_COUNT_1_BIT, "colour target");
  depth_ = createImage2D(ctx, extent, kDepthFormat, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | readable,
                         VK_SAMPLE_COUNT_1_BIT, "depth target");
  if (multisampled()) {
    colorMsaa_ = createImage2D(ctx, extent, kColorFormat, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, samples,
                               "colour target (MSAA)");
    depthMsaa_ = createImage2D(ctx, extent, kDepthFormat, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, samples,
                               "depth target (MSAA)");
  }
}

}  // namespace vegstream::render
