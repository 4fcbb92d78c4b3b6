#pragma once
// Offscreen colour + depth targets. With MSAA (samples > 1) the multisampled attachments are
// resolved at the end of rendering — colour by averaging, depth by taking sample 0 — into
// single-sample images that can be copied, presented or read back. With samples == 1 the
// attachments are those images themselves.

#include "render/gpu_resources.h"

namespace vegstream::render {

// sRGB storage: shaders work in linear light, MSAA resolve averages in linear light, and the
// bytes read back are display-ready.
constexpr VkFormat kColorFormat = VK_FORMAT_R8G8B8A8_SRGB;
// Reverse-Z float depth: near → 1, far → 0, for precision from 1 m to 100 km.
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;

class RenderTargets {
 public:
  RenderTargets(const Context& ctx, VkExtent2D extent, VkSampleCountFlagBits samples);

  VkExtent2D extent() const { return extent_; }
  VkSampleCountFlagBits samples() const { return samples_; }
  bool multisampled() const { return samples_ != VK_SAMPLE_COUNT_1_BIT; }

  const GpuImage& colorAttachment() const { return multisampled() ? colorMsaa_ : color_; }
  const GpuImage& depthAttachment() const { return multisampled() ? depthMsaa_ : depth_; }
  const GpuImage& color() const { return color_; }  // single-sample, after resolve
  const GpuImage& depth() const { return depth_; }  // single-sample, after resolve

  // Clears every target and begins dynamic rendering into them (resolving to color() and
  // depth() when multisampled), viewport and scissor over the whole extent.
  void beginRendering(VkCommandBuffer cmd) const;

 private:
  VkExtent2D extent_;
  VkSampleCountFlagBits samples_;
  GpuImage colorMsaa_, depthMsaa_;
  GpuImage color_, depth_;
};

}  // namespace vegstream::render
