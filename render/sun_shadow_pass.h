#pragma once
// The sun's cascaded shadow map (issue 20, render/shadow_cascades.h for the matrices): one D32
// layer per cascade, bound to set 0 binding 4 of every pass (shaders/common/sun_shadow.glsl) with
// a comparison sampler. record() clears each cascade and lets the caller draw its casters (the
// trees: render/tree_pass.h) with the cascade's matrix; the grass keeps its planar shadows.
// Until a frame draws casters the map is cleared (everything lit) and frames say so with
// FrameUniforms::shadowSplits.w = 0.

#include <array>
#include <functional>

#include <glm/mat4x4.hpp>

#include "render/context.h"
#include "render/gpu_resources.h"
#include "render/handle.h"
#include "render/shadow_cascades.h"

namespace vegstream::render {

class SunShadowPass {
 public:
  SunShadowPass(const Context& ctx, uint32_t mapSize);

  // Binds the map to `frameSet` binding 4; `placeholder`: a cleared 1 × 1 map instead — for the
  // set the shadow pass itself draws with, while the map is a depth attachment.
  void writeFrameSet(VkDescriptorSet frameSet, bool placeholder = false) const;
  uint32_t mapSize() const { return size_; }
  uint64_t gpuBytes() const { return map_.bytes + placeholder_.bytes; }

  using DrawCasters = std::function<void(VkCommandBuffer, int cascade, const glm::mat4& matrix)>;
  // Outside rendering: the cascades in `cascades.drawn` (render/shadow_refresh.h) cleared and
  // drawn, the others kept as earlier frames drew them; then the map readable by fragment and
  // compute shaders.
  void record(VkCommandBuffer cmd, const ShadowCascades& cascades, const DrawCasters& draw) const;

 private:
  const Context* ctx_;
  uint32_t size_;
  GpuImage map_, placeholder_;
  std::array<ImageView, kShadowCascades> layers_;
  Sampler sampler_;
};

}  // namespace vegstream::render
