// Terrain types from the species catalog, core seed ../shared/seeds/001_3eca9f2c7752e4fb.txt
// §3.3 (eq. 16 used once: the same scores choose species and blend the terrain's detail).
#include "vegetation/terrain_types.h"

#include <cassert>

namespace vegstream::vegetation {

std::vector<TerrainType> terrainTypesOf(const SpeciesCatalog& catalog) {
  assert(catalog.species.size() <= kMaxTerrainTypes);
  std::vector<TerrainType> out;
  out.reserve(catalog.species.size());
  // A tree species that claims no ground (tree_niche.h) is no type of ground either.
  for (const Species& s : catalog.species)
    if (!isTree(s) || s.tree.claimsGround) out.push_back({s.name, s.score, s.surface});
  return out;
}

std::span<const TerrainType> defaultTerrainTypes() {
  static const std::vector<TerrainType> types = terrainTypesOf(defaultSpeciesCatalog());
  return types;
}

std::vector<ColourScoreParams> scoreParams(std::span<const TerrainType> types) {
  std::vector<ColourScoreParams> out;
  out.reserve(types.size());
  for (const TerrainType& t : types) out.push_back(t.score);
  return out;
}

std::vector<float> terrainTypeWeights(std::span<const TerrainType> types, glm::vec3 hsv, float ndvi) {
  std::vector<ColourScoreParams> sharper = scoreParams(types);
  for (ColourScoreParams& p : sharper) p.p *= kTerrainBlendSharpness;  // s^k = d^(−p k)
  return blendWeights(sharper, hsv, ndvi);
}

std::vector<float> surfaceWeights(std::span<const TerrainType> types, glm::vec3 hsv, float ndvi) {
  const std::vector<float> w = terrainTypeWeights(types, hsv, ndvi);
  std::vector<float> out(kDetailSurfaceCount, 0.0f);
  for (size_t i = 0; i < types.size(); ++i) out[static_cast<size_t>(types[i].surface)] += w[i];
  return out;
}

size_t dominantTerrainType(std::span<const TerrainType> types, glm::vec3 hsv, float ndvi) {
  assert(!types.empty());
  return bestMatch(scoreParams(types), hsv, ndvi);
}

}  // namespace vegstream::vegetation
