#pragma once
// The sky and the air (issue 39 item 2; Hillaire 2020, shaders/common/atmosphere_model.glsl):
// four compute passes over small LUTs —
//   transmittance (256 × 64) and multiple scattering (32 × 32): the atmosphere's alone, made when
//   the pass is created;
//   sky view (192 × 108) and aerial perspective (32 × 64 × 32, sun-relative directions × distance):
//   each frame, from the camera's altitude and the sun;
//   the sky light: the sun's illuminance at the camera and the sky's irradiance, integrated over
//   the sky view, in a small buffer.
// Every pass reads them through set 0 (bindings 7–9, shaders/common/atmosphere.glsl): the sky,
// the light on the terrain, plants and trees, and the aerial perspective are one model.
//
// Contract: record() runs outside rendering, before any pass that reads set 0's bindings 7–9;
// it leaves the LUTs in SHADER_READ_ONLY_OPTIMAL and the buffer readable by every stage.

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "render/atmosphere_luts.h"
#include "render/gpu_resources.h"
#include "render/handle.h"

namespace vegstream::render {

inline constexpr float kAerialFarKm = 120.0f;  // the aerial volume's last slice
inline constexpr VkExtent2D kTransmittanceLutSize{256, 64};
inline constexpr VkExtent2D kMultiScatteringLutSize{32, 32};
inline constexpr VkExtent2D kSkyViewLutSize{192, 108};
inline constexpr uint32_t kAerialLutSize[3] = {32, 64, 32};
// Ψ_ms is integrated over n × 2n directions of 20 steps (= atmosphere_multiscatter.comp's).
inline constexpr int kMultiScatteringDirections = 10;

// The camera's radius from the planet's centre (km) for a height MSL (m), kept 1 m above the
// atmosphere's ground so a camera below sea level (the Dead Sea) still has sky above it.
float atmosphereCameraRadiusKm(double heightMslM);

struct AtmospherePush {
  glm::vec4 view;  // x: camera radius (km), y: the sun's cosine with the up, z: aerial far (km), w: 1 = multiple scattering
};

class AtmospherePass {
 public:
  explicit AtmospherePass(const Context& ctx);

  // `sunDirection`: unit, towards the sun, local ENU; `multipleScattering` off: single
  // scattering only (the reference test compares each order).
  void record(VkCommandBuffer cmd, double cameraHeightMslM, const glm::vec3& sunDirection,
              bool multipleScattering = true) const;

  // Set 0's bindings 7 (sky view), 8 (aerial volume) and 9 (sky light).
  void writeFrameSet(VkDescriptorSet set) const;

  // Every LUT and the sky light, copied to the host (waits for the device to be idle first).
  AtmosphereLuts readBack() const;

  const GpuImage& transmittance() const { return transmittance_; }
  const GpuImage& multiScattering() const { return multiScattering_; }
  const GpuImage& skyView() const { return skyView_; }
  const GpuImage& aerial() const { return aerial_; }
  VkBuffer skyLight() const { return skyLight_.get(); }

 private:
  void recordStaticLuts(VkCommandBuffer cmd) const;

  const Context* ctx_;
  GpuImage transmittance_, multiScattering_, skyView_, aerial_;
  GpuBuffer skyLight_;
  Sampler linear_;
  DescriptorSetLayout setLayout_;
  DescriptorPool pool_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  PipelineLayout layout_;
  Pipeline transmittancePipe_, multiScatteringPipe_, viewPipe_, skyLightPipe_;
};

}  // namespace vegstream::render
