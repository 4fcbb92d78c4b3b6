#pragma once
// Cascaded sun shadow maps (issue 20; Engel, "Cascaded Shadow Maps", ShaderX5 2006; Dimitrov,
// "Cascaded Shadow Maps", NVIDIA 2007): the view is split by distance into kShadowCascades slices,
// each covered by an orthographic map seen from the sun. Each cascade holds its slice's bounding
// sphere (so its size does not change as the camera turns), and its centre is snapped to whole
// texels in world-anchored coordinates (so the shadows do not shimmer as the camera moves).
// Plain maths, no Vulkan: the frame uniforms carry the matrices to every pass that samples the
// map (shaders/common/sun_shadow.glsl), the tree pass draws into it with the same matrices.

#include <array>
#include <cstdint>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "geo/camera.h"

namespace vegstream::render {

using geo::Camera;

inline constexpr int kShadowCascades = 3;

struct ShadowCascades {
  // Camera-relative position → the cascade's clip space: x, y in [−1, 1], depth 1 nearest the
  // sun … 0 farthest (reverse-Z, as the frame).
  std::array<glm::mat4, kShadowCascades> matrices{};
  glm::vec4 splits{0.0f};  // xyz: each cascade's far view distance (m), w: 1 when shadows are on
  std::array<float, kShadowCascades> texelM{};  // world size of one texel per cascade
  // The cascades this frame draws (bit c: cascade c); the others keep what an earlier frame drew
  // (render/shadow_refresh.h). The trees' classify casts into these only.
  uint32_t drawn = (1u << kShadowCascades) - 1;
};

struct ShadowSettings {
  uint32_t mapSize = 1024;                                   // texels per side of each cascade
  // Far distances: beyond 600 m a tree's shadow is a few pixels at 1080p; the H200 spent 21 ms a
  // frame drawing the impostors of a 1200 m cascade over the Kolob forest.
  std::array<float, kShadowCascades> splitsM{40.0f, 180.0f, 600.0f};
  float casterMarginM = 400.0f;  // how far towards the sun casters may stand outside a slice
};

// The cascades for `camera` (its position: the local ENU frame) lit from `towardsSun`.
ShadowCascades shadowCascades(const Camera& camera, double aspect, const glm::dvec3& towardsSun,
                              const ShadowSettings& settings);

}  // namespace vegstream::render
