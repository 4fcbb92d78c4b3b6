#pragma once
// Terrain types: the ground kinds the colour score (vegetation/colour_score.h, core seed
// ../shared/seeds/001_3eca9f2c7752e4fb.txt §3.3 eq. 16) tells apart in the imagery, each with
// its reference colour and the surface detail drawn on it close up. The render pass blends the
// detail textures by the types' blend weights (render/terrain_detail.h uploads this table; it
// is the one source of truth for the CPU and the GPU).
//
// The default table is tuned for the sample datasets (Zion's plateau forest, meadows, red and
// white sandstone, gravel washes; Goleta's lawns and grey streets): reference colours are HSV of
// the 8-bit imagery as imported (datasets/: a p1–p99 stretch of the Landsat bands).

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "vegetation/colour_score.h"

namespace vegstream::vegetation {

// The detail pattern drawn on a terrain type close up; one detail-texture layer each, in this
// order (render/detail_textures.h).
enum class DetailSurface : uint32_t { Grass = 0, Rock = 1, Gravel = 2, Sand = 3 };
inline constexpr uint32_t kDetailSurfaceCount = 4;

struct TerrainType {
  std::string_view name;
  ColourScoreParams score;
  DetailSurface surface = DetailSurface::Grass;
};

// The GPU uniform block holds at most this many types (render/terrain_detail.h).
inline constexpr size_t kMaxTerrainTypes = 8;

// The default table (see terrain_types.cpp for each entry's reasoning).
std::span<const TerrainType> defaultTerrainTypes();

// The score parameters of `types`, in order (for blendWeights / bestMatch).
std::vector<ColourScoreParams> scoreParams(std::span<const TerrainType> types);

// Blend weights of `types` for base colour `hsv` (sums to 1).
std::vector<float> terrainTypeWeights(std::span<const TerrainType> types, glm::vec3 hsv);

// The detail surfaces' weights: the types' blend weights summed per surface (sums to 1).
std::vector<float> surfaceWeights(std::span<const TerrainType> types, glm::vec3 hsv);

// Index of the type that scores highest for `hsv`; `types` must not be empty.
size_t dominantTerrainType(std::span<const TerrainType> types, glm::vec3 hsv);

}  // namespace vegstream::vegetation
