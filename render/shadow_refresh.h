#pragma once
// Which of the sun's shadow cascades a frame draws again (render/sun_shadow_pass.h), and the
// matrices of those it keeps. One cascade a frame, in turns of four frames: the nearest (to 40 m)
// every other frame, the two farther ones (to 180 and 600 m) every fourth. Its casters are the
// trees, whose sway moves a shadow little in 33 or 67 ms; the camera's motion moves none, because
// a kept layer is read with the matrix it was drawn with, moved to this frame's camera (positions
// are camera-relative), so its shadows stay where they were in the world. On the H200 each
// cascade's clear alone is about 0.07 ms (a 1024² D32 layer), and the shadow pass was the third
// largest of benchmark-30s's slowest frames. Every cascade is drawn when it has not been yet,
// after a frame without shadows, when the sun has turned, and a cascade whenever the camera has
// moved more than a twentieth of its reach since it was drawn (a fast flight near the ground
// redraws the nearest one every frame). Plain maths, no Vulkan; deterministic (the frame index
// decides the turns).

#include <array>
#include <cstdint>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "render/shadow_cascades.h"

namespace vegstream::render {

class ShadowRefresh {
 public:
  // This frame's cascades (fresh from shadowCascades) → which to draw, set in `cascades.drawn`
  // (bit c: cascade c) and returned; the kept ones' matrices are replaced by the ones their layers hold.
  uint32_t plan(ShadowCascades& cascades, const glm::dvec3& camera, const glm::dvec3& towardsSun, uint64_t frame);
  // A frame without shadows: the layers are no longer this flight's.
  void reset() { drawn_ = {}; }

 private:
  struct Drawn {
    bool valid = false;
    glm::dvec3 camera{0.0};  // where the camera was when the layer was drawn
    glm::mat4 matrix{1.0f};  // its matrix then
  };
  std::array<Drawn, kShadowCascades> drawn_{};
  glm::dvec3 sun_{0.0};
};

}  // namespace vegstream::render
