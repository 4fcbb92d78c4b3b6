#pragma once
// The base colour under a point, sampled from one imagery tile exactly as the GPU classify pass
// samples its imagery layer (shaders/common/seeding.glsl, imageryBilinear): texel centres at
// (i + ½) / size, clamped to the edge, each texel sRGB-decoded to linear first, then bilinear in
// linear light — a hand-written fetch rather than the texture unit, whose filtering precision
// differs between devices, so the CPU reference and the GPU agree.

#include <cstdint>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace vegstream::vegetation {

struct ImageryTexels {
  const uint8_t* rgba = nullptr;  // size × size × 4 bytes, sRGB, rows from the north
  uint32_t size = 256;
};

// Linear RGB at texture coordinates uv (0 … 1 across the tile, v southwards).
glm::vec3 sampleImageryLinear(const ImageryTexels& tile, glm::vec2 uv);

}  // namespace vegstream::vegetation
