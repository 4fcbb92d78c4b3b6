#pragma once
// Exposure and tone mapping (issue 39 item 3; shaders/common/exposure.glsl): after the scene
// has been resolved into the linear HDR colour target, three compute dispatches — the frame's
// log-luminance histogram, the exposure (automatic from it, fixed, or identity), and AgX tone
// mapping into the sRGB display target — which the HUD draws over, the read-back copies and the
// window presents. The exposure each frame used is read back per frame slot.
//
// Contract: record() runs outside rendering, after the frame's last scope has resolved into
// RenderTargets::color() (COLOR_ATTACHMENT_OPTIMAL); it leaves display() in
// COLOR_ATTACHMENT_OPTIMAL and color() in GENERAL (each frame discards it at its start).

#include <array>
#include <optional>

#include <glm/vec4.hpp>

#include "render/frame_slots.h"
#include "render/gpu_resources.h"
#include "render/handle.h"
#include "render/render_targets.h"

namespace vegstream::render {

// How a frame's HDR becomes display values (exposure.glsl's kTone*).
enum class ToneMode : uint32_t { Auto = 0, Fixed = 1, Identity = 2 };

// Push constants of exposure_resolve.comp and tonemap.comp.
struct TonemapPush {
  glm::vec4 params;   // x: ToneMode, y: fixed EV100, z: 1 = adapt over time, w: seconds since the last frame
  glm::uvec4 target;  // x: frame slot, y, z: width, height
};
static_assert(sizeof(TonemapPush) == 32);

inline constexpr uint32_t kExposureBins = 64;  // = exposure.glsl's kExposureBins
inline constexpr float kLuminanceUnitCdM2 = 1.0e4f;  // = exposure.glsl's

struct ToneSettings {
  ToneMode mode = ToneMode::Auto;
  float fixedEv = 0.0f;
  bool adapt = false;     // smooth the automatic exposure over time (the window)
  float frameSeconds = 0.0f;
};

class TonemapPass {
 public:
  TonemapPass(const Context& ctx, const RenderTargets& targets);

  void record(VkCommandBuffer cmd, int slot, const ToneSettings& settings, const RenderTargets& targets) const;
  // The EV100 slot's last frame was tone-mapped with (after its fence).
  float exposureEv(int slot) const;

 private:
  DescriptorSetLayout setLayout_;
  DescriptorPool pool_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  GpuBuffer state_;     // ExposureState (device-local)
  GpuBuffer readback_;  // one float per frame slot (host-visible)
  PipelineLayout layout_;
  Pipeline histogram_, resolve_, tonemap_;
};

}  // namespace vegstream::render
