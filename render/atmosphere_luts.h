#pragma once
// The atmosphere's LUTs as read back (Renderer::readAtmosphere; render/atmosphere_pass.h): plain
// data for tests and diagnostics. Texel i of a LUT n wide holds the parameter u = i / (n − 1)
// (shaders/common/atmosphere_lut_io.glsl); rows from v = 0.

#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec4.hpp>

namespace vegstream::render {

struct LutImage {
  uint32_t width = 0, height = 0, depth = 1;
  std::vector<glm::vec4> texels;  // x fastest, then y, then z
  const glm::vec4& at(uint32_t x, uint32_t y, uint32_t z = 0) const { return texels[(z * height + y) * width + x]; }
};

struct AtmosphereLuts {
  LutImage transmittance, multiScattering, skyView, aerial;
  // The frame's light: sun illuminance (w: the sun's cosine), sky irradiance up, side, down.
  std::array<glm::vec4, 4> skyLight{};
};

}  // namespace vegstream::render
