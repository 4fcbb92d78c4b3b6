#pragma once
// The HUD pass: draws an OverlayDrawData (overlay_types.h) over the resolved single-sample
// colour target with one alpha-blended pipeline, one sampled texture (the font atlas) and
// per-frame-slot host-visible vertex/index buffers. Runs after the scene's rendering ends, so
// read-backs and the present blit include it.

#include <array>
#include <cstdint>
#include <functional>

#include "render/gpu_resources.h"
#include "render/handle.h"
#include "render/frame_slots.h"
#include "render/overlay_types.h"

namespace vegstream::render {

class HudPass {
 public:
  static constexpr int kSlots = kFramesInFlight;  // one buffer set per frame in flight

  explicit HudPass(const Context& ctx);

  // Records the overlay into `target` (COLOR_ATTACHMENT_OPTIMAL before and after). `slot`'s
  // previous frame must have completed. Buffers and textures it replaces go to `retire`, which
  // keeps them alive until this frame has finished on the GPU. Returns the triangles drawn.
  uint64_t record(VkCommandBuffer cmd, int slot, const OverlayDrawData& data, const GpuImage& target,
                  const std::function<void(GpuBuffer&&)>& retireBuffer,
                  const std::function<void(GpuImage&&)>& retireImage);

 private:
  void uploadTexture(VkCommandBuffer cmd, const OverlayImage& image,
                     const std::function<void(GpuBuffer&&)>& retireBuffer,
                     const std::function<void(GpuImage&&)>& retireImage);
  void ensureCapacity(GpuBuffer& buffer, VkDeviceSize bytes, VkBufferUsageFlags usage, const char* what, int slot,
                      const std::function<void(GpuBuffer&&)>& retire);

  const Context* ctx_;
  DescriptorSetLayout setLayout_;
  DescriptorPool pool_;
  std::array<VkDescriptorSet, kSlots> sets_{};  // per slot: rewritten only when that slot's last frame is done
  std::array<uint64_t, kSlots> setTextureId_{};
  PipelineLayout layout_;
  Pipeline pipeline_;
  Sampler sampler_;
  GpuImage texture_;
  uint64_t textureId_ = 0;  // OverlayImage::id of texture_; 0: none yet
  std::array<GpuBuffer, kSlots> vertices_, indices_;
};

}  // namespace vegstream::render
