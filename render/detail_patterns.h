#pragma once
// The terrain detail patterns, generated on the CPU (no Vulkan here): one square RGBA8 image
// per vegetation::DetailSurface — grass blade streaks, rock strata and cracks, gravel pebbles,
// sand ripples — each tiling seamlessly (every noise lattice wraps at the image's edge) and
// deterministic (integer hashing only: the same bytes on every machine).
//
// The values are *modulation* factors in UNORM: the terrain shader multiplies the albedo by
// 2 × texel, so 128 (0.5) leaves the imagery unchanged. Each channel of each layer is
// normalised to mean 0.5, so the detail changes the look close up but not the average colour,
// and the coarsest mip levels (what distance filtering reaches) are neutral.

#include <cstdint>
#include <vector>

#include "vegetation/terrain_types.h"

namespace vegstream::render {

inline constexpr uint32_t kDetailTextureSize = 256;

// One layer, size × size texels, RGBA8 row-major (alpha 255). size: a power of two ≥ 16.
std::vector<uint8_t> generateDetailPattern(vegetation::DetailSurface surface, uint32_t size);

// Mip levels of a square power-of-two size (size, size/2, …, 1).
uint32_t mipLevelCount(uint32_t size);

// `level0` followed by every smaller mip level down to 1 × 1 (2 × 2 box filter), packed.
std::vector<uint8_t> withMipChain(const std::vector<uint8_t>& level0, uint32_t size);

// Every surface's layer with its mip chain, layer after layer (the staging layout of
// recordImageArrayUpload in gpu_resources.h). Generated once per process and kept.
const std::vector<uint8_t>& detailTextureData();

}  // namespace vegstream::render
