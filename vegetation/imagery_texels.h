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
  // The NDVI tile over it (datasets/tile_codec.h's byte encoding, 0 = none), or null.
  const uint8_t* ndvi = nullptr;
};

// Linear RGB at texture coordinates uv (0 … 1 across the tile, v southwards).
glm::vec3 sampleImageryLinear(const ImageryTexels& tile, glm::vec2 uv);

// NDVI at uv: bilinear over the same four texels, the weights of those without NDVI dropped
// and the rest renormalised; kNoNdvi (colour_score.h) when none of the four has NDVI or the
// tile has no NDVI layer. classify.comp's imageryNdvi does the same in the same order.
float sampleImageryNdvi(const ImageryTexels& tile, glm::vec2 uv);

}  // namespace vegstream::vegetation
