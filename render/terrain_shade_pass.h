#pragma once
// Deferred terrain shading, the compute half (shaders/common/terrain_shade.glsl): after the
// terrain's visibility pass has left per sample which triangle it sees, one dispatch shades
// every pixel — the terrain with the forward path's own code (terrain_shading.glsl), the sky
// where no triangle is — and stores the colours straight into the colour attachment through
// its storage view. The sky pass is then not drawn at all.
//
// Why: on GPUs whose graphics units are a small part of the chip (NVIDIA H100/H200: fragment
// shading on two of 66 TPCs, a handful of ROPs) the terrain's per-fragment detail shading and
// the full-screen sky writes were the frame's largest cost; compute runs on every SM and its
// stores bypass the ROPs. render/README.md has the measurements.
//
// Contract: the device supports storage images at the targets' sample count
// (DeviceInfo::supportsDeferredTerrain); record() runs outside rendering, after
// RenderTargets::visibilityToShade and the TerrainPass::prepare of the same slot.

#include <array>

#include "render/gpu_resources.h"
#include "render/handle.h"
#include "render/render_targets.h"
#include "render/terrain_pass.h"

namespace vegstream::render {

// Push constants of the terrain's compute passes (ShadePush in shaders/common/terrain_geometry.glsl).
struct TerrainComputePush {
  glm::uvec4 counts;  // x: pieces, y: triangles, z: binning phase, w: tile list capacity
  glm::uvec4 tiles;   // x, y: tiles across and down, z: samples per pixel
};
static_assert(sizeof(TerrainComputePush) == 32);

class TerrainShadePass {
 public:
  static constexpr int kSlots = TerrainPass::kSlots;

  TerrainShadePass(const Context& ctx, VkDescriptorSetLayout frameLayout, const TerrainPass& terrain,
                   const RenderTargets& targets);

  void record(VkCommandBuffer cmd, int slot, VkDescriptorSet frameSet, const TerrainPass& terrain,
              const RenderTargets& targets);

 private:
  const Context* ctx_;
  DescriptorSetLayout inputsLayout_;
  DescriptorPool pool_;
  Sampler nearest_;
  std::array<VkDescriptorSet, kSlots> inputs_{};
  PipelineLayout layout_;
  Pipeline pipeline_;
};

}  // namespace vegstream::render
