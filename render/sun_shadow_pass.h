#pragma once
// The sun's cascaded shadow map (issue 20, render/shadow_cascades.h for the matrices): one layer
// per cascade of reverse-Z depths as float bits in R32_UINT, bound to set 0 binding 4 of every
// pass (shaders/common/sun_shadow.glsl compares and filters) and, as a storage image, to the
// target set the casters are rasterised into in compute with atomic max (the trees:
// render/tree_pass.h, shaders/tree_shadow_raster.comp; the H100's and H200's few graphics units
// made depth-only draws the slowest way to fill it). record() clears each cascade drawn and lets
// the caller dispatch its casters with the cascade's matrix; the grass keeps its planar shadows.
// Until a frame draws casters the map is cleared (everything lit) and frames say so with
// FrameUniforms::shadowSplits.w = 0.

#include <cstdint>
#include <functional>
#include <vector>

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

  // The target set's layout (binding 0: the map's layers as a storage image, compute): the
  // casters' pipelines are made with it.
  VkDescriptorSetLayout targetLayout() const { return targetLayout_.get(); }

  // Records the casters of `cascade` into layer `cascade` of `target` (targetLayout()'s set) with
  // the cascade's matrix: compute writes (atomic max of the depth bits) only.
  using DrawCasters =
      std::function<void(VkCommandBuffer, int cascade, const glm::mat4& matrix, VkDescriptorSet target)>;
  // Outside rendering: the cascades in `cascades.drawn` (render/shadow_refresh.h) cleared and
  // drawn, the others kept as earlier frames drew them; then the map readable by every stage that
  // samples it.
  void record(VkCommandBuffer cmd, const ShadowCascades& cascades, const DrawCasters& draw) const;

  // The map's layers as they are now (mapSize()² texels per cascade, row by row), for tests;
  // submits its own copy and waits for it (the caller has waited for the frames in flight).
  std::vector<uint32_t> read() const;

 private:
  const Context* ctx_;
  uint32_t size_;
  GpuImage map_, placeholder_;
  Sampler sampler_;
  DescriptorSetLayout targetLayout_;
  DescriptorPool targetPool_;
  VkDescriptorSet targetSet_ = VK_NULL_HANDLE;
};

}  // namespace vegstream::render
