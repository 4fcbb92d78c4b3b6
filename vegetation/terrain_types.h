#pragma once
// Terrain types: the ground kinds the colour score (vegetation/colour_score.h, core seed
// ../shared/seeds/001_3eca9f2c7752e4fb.txt §3.3 eq. 16) tells apart in the imagery, each with
// its reference colour and the surface detail drawn on it close up. The render pass blends the
// detail textures by the types' blend weights (render/terrain_detail.h uploads them).
//
// They are the species catalog's entries (issue 18: one table): each species, bare or not, is a
// terrain type with the same score and its `surface`, so the ground that grows grass is the
// ground drawn with the grass detail, and a catalog given with --species changes both.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "vegetation/colour_score.h"
#include "vegetation/species_catalog.h"

namespace vegstream::vegetation {

struct TerrainType {
  std::string name;
  ColourScoreParams score;
  DetailSurface surface = DetailSurface::Grass;
};

// The GPU uniform block holds at most this many types (render/terrain_detail.h): one per species.
inline constexpr size_t kMaxTerrainTypes = kMaxSpecies;

// The catalog's species as terrain types, in order, but for the tree species that claim no ground
// (TreeParams::claimsGround: they grow only among other trees, tree_niche.h).
std::vector<TerrainType> terrainTypesOf(const SpeciesCatalog& catalog);
// Those of the default catalog (config/species.json).
std::span<const TerrainType> defaultTerrainTypes();

// The score parameters of `types`, in order (for blendWeights / bestMatch).
std::vector<ColourScoreParams> scoreParams(std::span<const TerrainType> types);

// The terrain blends its detail by the types' scores raised to this power (normalised): the
// same eq. 16 scores as the species choice, sharper, so one detail dominates where one type's
// colour is — the catalog's p = 3 alone left a meadow colour only 35 % grass detail.
inline constexpr float kTerrainBlendSharpness = 3.0f;

// Blend weights of `types` for base colour `hsv` (sums to 1): score^kTerrainBlendSharpness, normalised.
std::vector<float> terrainTypeWeights(std::span<const TerrainType> types, glm::vec3 hsv, float ndvi = kNoNdvi);

// The detail surfaces' weights: the types' blend weights summed per surface (sums to 1).
std::vector<float> surfaceWeights(std::span<const TerrainType> types, glm::vec3 hsv, float ndvi = kNoNdvi);

// Index of the type that scores highest for `hsv`; `types` must not be empty.
size_t dominantTerrainType(std::span<const TerrainType> types, glm::vec3 hsv, float ndvi = kNoNdvi);

}  // namespace vegstream::vegetation
