// The default terrain-type table, core seed ../shared/seeds/001_3eca9f2c7752e4fb.txt §3.3
// (eq. 16; the weights follow the seed's advice: hue ignored for grey, value down-weighted
// because shadows change it).
#include "vegetation/terrain_types.h"

#include <array>
#include <cassert>

namespace vegstream::vegetation {
namespace {

// Reference colours are HSV of 8-bit sRGB imagery (h 0 red, 1/3 green), read off the imported
// Zion sample (its Landsat stretch is muted: greens are dark, the desert floor a greyish
// brown) and typical aerial photos (Goleta). Hue weighs 2 where the colour is saturated enough
// for its hue to mean something (a hue step of 0.1 ≈ 36° then counts as much as a saturation step
// of 0.25), value 0.4–0.6 because shadows change it. All types share p = 3.
constexpr float kP = 3.0f;

constexpr std::array kDefault{
    // Meadow and lawn: yellow-green, medium bright (sRGB ≈ 92 107 59; Zion's clearings in the
    // plateau forest, Goleta's lawns).
    TerrainType{"meadow", {{0.22f, 0.45f, 0.42f}, {2.0f, 0.8f, 0.4f}, kP}, DetailSurface::Grass},
    // Forest canopy: dark green (≈ 37 43 27, the Zion plateau); close up its floor of litter and
    // undergrowth, so gravel-like speckle.
    TerrainType{"forest", {{0.23f, 0.38f, 0.17f}, {2.0f, 0.8f, 0.6f}, kP}, DetailSurface::Gravel},
    // Red (Kayenta / lower Navajo) sandstone walls and slickrock: orange-red (≈ 148 101 86).
    TerrainType{"red rock", {{0.04f, 0.42f, 0.58f}, {2.0f, 0.8f, 0.4f}, kP}, DetailSurface::Rock},
    // Gravel, soil and scree of the desert floor: muted red-brown, darker (≈ 107 88 79).
    TerrainType{"gravel", {{0.05f, 0.26f, 0.42f}, {2.0f, 0.8f, 0.4f}, kP}, DetailSurface::Gravel},
    // Pale (upper Navajo) sandstone: nearly white, a trace of warm hue (≈ 184 175 162); little
    // saturation, so hue counts less.
    TerrainType{"pale sandstone", {{0.10f, 0.12f, 0.72f}, {0.4f, 1.0f, 0.6f}, kP}, DetailSurface::Rock},
    // Bare grey rock, roads, concrete (≈ 107 103 103): no saturation, so hue is meaningless (weight 0).
    TerrainType{"grey rock", {{0.0f, 0.04f, 0.42f}, {0.0f, 1.2f, 0.4f}, kP}, DetailSurface::Rock},
    // Sand and dry washes: pale warm yellow, more saturated than pale sandstone (≈ 194 173 132).
    TerrainType{"sand", {{0.11f, 0.32f, 0.76f}, {2.0f, 1.0f, 0.5f}, kP}, DetailSurface::Sand},
};
static_assert(kDefault.size() <= kMaxTerrainTypes, "the GPU block holds kMaxTerrainTypes");

}  // namespace

std::span<const TerrainType> defaultTerrainTypes() { return kDefault; }

std::vector<ColourScoreParams> scoreParams(std::span<const TerrainType> types) {
  std::vector<ColourScoreParams> out;
  out.reserve(types.size());
  for (const TerrainType& t : types) out.push_back(t.score);
  return out;
}

std::vector<float> terrainTypeWeights(std::span<const TerrainType> types, glm::vec3 hsv) {
  return blendWeights(scoreParams(types), hsv);
}

std::vector<float> surfaceWeights(std::span<const TerrainType> types, glm::vec3 hsv) {
  const std::vector<float> w = terrainTypeWeights(types, hsv);
  std::vector<float> out(kDetailSurfaceCount, 0.0f);
  for (size_t i = 0; i < types.size(); ++i) out[static_cast<size_t>(types[i].surface)] += w[i];
  return out;
}

size_t dominantTerrainType(std::span<const TerrainType> types, glm::vec3 hsv) {
  assert(!types.empty());
  return bestMatch(scoreParams(types), hsv);
}

}  // namespace vegstream::vegetation
