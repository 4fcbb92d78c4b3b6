// The terrain types are the species catalog's (issue 18: one table): sane entries, and the colour
// score picks the type a person would for typical imagery colours of the samples (8-bit sRGB as
// imported).

#include "vegetation/terrain_types.h"

#include <cstdio>
#include <set>
#include <string>

#include <gtest/gtest.h>

namespace vegstream::vegetation {
namespace {

std::string pick(uint8_t r, uint8_t g, uint8_t b) {
  const auto types = defaultTerrainTypes();
  return std::string(types[dominantTerrainType(types, hsvFromSrgb8(r, g, b))].name);
}

TEST(TerrainTypes, TheDefaultTableIsWellFormed) {
  const auto types = defaultTerrainTypes();
  ASSERT_GE(types.size(), 4u);
  ASSERT_LE(types.size(), kMaxTerrainTypes);
  std::set<std::string> names;
  std::set<DetailSurface> surfaces;
  for (const TerrainType& t : types) {
    EXPECT_TRUE(names.insert(t.name).second) << "duplicate " << t.name;
    surfaces.insert(t.surface);
    EXPECT_GT(t.score.p, 0.0f) << t.name;
    for (int c = 0; c < 3; ++c) {
      EXPECT_GE(t.score.weights[c], 0.0f) << t.name;
      EXPECT_GE(t.score.reference[c], 0.0f) << t.name;
      EXPECT_LE(t.score.reference[c], 1.0f) << t.name;
    }
    EXPECT_LT(t.score.reference.x, 1.0f) << t.name;
    EXPECT_LT(static_cast<uint32_t>(t.surface), kDetailSurfaceCount) << t.name;
  }
  EXPECT_EQ(surfaces.size(), size_t{kDetailSurfaceCount}) << "every detail layer is used by some type";
  for (const char* want :
       {"grass", "conifer", "red gravel", "dry tufts", "pale sandstone", "grey rock", "sand", "broadleaf"})
    EXPECT_TRUE(names.count(want)) << want;
  // The same entries as the catalog, in its order: the species' scores and their surfaces; the
  // tree species that claim no ground (tree_niche.h) are no ground type.
  const SpeciesCatalog& c = defaultSpeciesCatalog();
  std::vector<const Species*> ground;
  for (const Species& s : c.species)
    if (!isTree(s) || s.tree.claimsGround) ground.push_back(&s);
  ASSERT_EQ(types.size(), ground.size());
  ASSERT_LT(ground.size(), c.species.size());
  for (size_t i = 0; i < types.size(); ++i) {
    EXPECT_EQ(types[i].name, ground[i]->name);
    EXPECT_EQ(types[i].score.reference, ground[i]->score.reference);
    EXPECT_EQ(types[i].surface, ground[i]->surface);
  }
}

TEST(TerrainTypes, ACatalogsSurfacesFollowItsKindsUnlessGiven) {
  const auto parsed = parseSpeciesCatalog(R"({"species": [
    {"name": "a", "reference": {"srgb": "#406030"}, "weights": {"h": 1, "s": 1, "v": 1}, "p": 2, "kind": "grass",
     "height_m": {"min": 0.1, "max": 0.2}, "stiffness": {"min": 1, "max": 2}, "width_m": {"min": 0.01, "max": 0.02},
     "colour_modulation": {"min": 1, "max": 1}},
    {"name": "b", "reference": {"srgb": "#204010"}, "weights": {"h": 1, "s": 1, "v": 1}, "p": 2, "kind": "tree",
     "height_m": {"min": 5, "max": 9}, "stiffness": {"min": 5, "max": 9}, "width_m": {"min": 1, "max": 2},
     "colour_modulation": {"min": 1, "max": 1}, "tree": {"form": "conifer", "density_ha": 100, "spacing_m": 3}},
    {"name": "c", "reference": {"srgb": "#808080"}, "weights": {"h": 0, "s": 1, "v": 1}, "p": 2, "bare": true},
    {"name": "d", "reference": {"srgb": "#d0c080"}, "weights": {"h": 1, "s": 1, "v": 1}, "p": 2, "bare": true,
     "surface": "sand"}]})", "test");
  ASSERT_TRUE(parsed.ok()) << parsed.error().message;
  const std::vector<TerrainType> t = terrainTypesOf(*parsed);
  ASSERT_EQ(t.size(), 4u);
  EXPECT_EQ(t[0].surface, DetailSurface::Grass);
  EXPECT_EQ(t[1].surface, DetailSurface::Gravel);
  EXPECT_EQ(t[2].surface, DetailSurface::Rock);
  EXPECT_EQ(t[3].surface, DetailSurface::Sand);
  const auto bad = parseSpeciesCatalog(R"({"species": [{"name": "c", "reference": {"srgb": "#808080"},
    "weights": {"h": 0, "s": 1, "v": 1}, "p": 2, "bare": true, "surface": "lava"}]})", "test");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("species[0].surface"), std::string::npos) << bad.error().message;
}

// Colours read off the imported Zion sample (10 × 10 pixel means) and typical aerial photos.
TEST(TerrainTypes, TypicalImageryColoursPickTheirType) {
  EXPECT_EQ(pick(104, 120, 60), "grass");            // a bright clearing
  EXPECT_EQ(pick(92, 122, 52), "grass");             // Goleta lawn
  EXPECT_EQ(pick(0x38, 0x40, 0x31), "grass");        // the Kolob meadow of the coverage test
  EXPECT_EQ(pick(0x1c, 0x24, 0x19), "conifer");      // Zion plateau forest
  EXPECT_EQ(pick(0x14, 0x1c, 0x0d), "conifer");      // forest in shadow
  EXPECT_EQ(pick(149, 101, 88), "red gravel");       // Zion red sandstone (Kolob)
  EXPECT_EQ(pick(106, 86, 77), "red gravel");        // Zion desert floor
  EXPECT_EQ(pick(184, 177, 164), "pale sandstone");  // Zion white (upper Navajo) sandstone
  EXPECT_EQ(pick(208, 196, 176), "pale sandstone");  // brighter still
  EXPECT_EQ(pick(128, 128, 130), "grey rock");       // grey rock, a street
  EXPECT_EQ(pick(90, 92, 95), "grey rock");          // darker grey: hue ignored, value down-weighted
  EXPECT_EQ(pick(214, 188, 138), "sand");            // pale yellow sand
}

TEST(TerrainTypes, SurfaceWeightsSumPerDetailLayer) {
  const auto types = defaultTerrainTypes();
  for (glm::vec3 hsv : {hsvFromSrgb8(104, 120, 60), hsvFromSrgb8(149, 101, 88), hsvFromSrgb8(10, 10, 200)}) {
    const auto t = terrainTypeWeights(types, hsv);
    const auto s = surfaceWeights(types, hsv);
    ASSERT_EQ(t.size(), types.size());
    ASSERT_EQ(s.size(), size_t{kDetailSurfaceCount});
    float sumT = 0.0f, sumS = 0.0f;
    for (float w : t) sumT += w;
    for (float w : s) sumS += w;
    EXPECT_NEAR(sumT, 1.0f, 1e-5f);
    EXPECT_NEAR(sumS, 1.0f, 1e-5f);
  }
  EXPECT_GT(surfaceWeights(types, hsvFromSrgb8(104, 120, 60))[size_t(DetailSurface::Grass)], 0.6f);
  // Red sandstone: mostly rock detail (the red gravel's slickrock), the dry tufts' gravel beside.
  EXPECT_GT(surfaceWeights(types, hsvFromSrgb8(149, 101, 88))[size_t(DetailSurface::Rock)], 0.5f);
  // A colour halfway (in HSV) between meadow and forest has a good share of both.
  ASSERT_EQ(types[0].name, "grass");
  ASSERT_EQ(types[1].name, "conifer");
  const auto between = terrainTypeWeights(types, 0.5f * (types[0].score.reference + types[1].score.reference));
  EXPECT_GT(between[0], 0.1f);  // (the blend is sharpened: kTerrainBlendSharpness)
  EXPECT_GT(between[1], 0.1f);
  EXPECT_GT(between[0] + between[1], 0.8f);
}

// The one table scores NDVI for the terrain's detail as for the species: a dark green that the
// colour alone gives grass detail loses it where the NDVI says bare ground (rock detail comes in)
// and gets none of the rock where the NDVI says plants; without NDVI it is scored as before.
TEST(TerrainTypes, NdviMovesTheDetailOfADarkGreenLikeTheSpeciesChoice) {
  const std::span<const TerrainType> types = defaultTerrainTypes();
  const glm::vec3 darkGreen = hsvFromSrgb8(24, 30, 18);
  const auto grass = size_t(DetailSurface::Grass);
  const std::vector<float> none = surfaceWeights(types, darkGreen);
  EXPECT_EQ(none, surfaceWeights(types, darkGreen, kNoNdvi));
  const std::vector<float> rock = surfaceWeights(types, darkGreen, 0.08f);
  const std::vector<float> plants = surfaceWeights(types, darkGreen, 0.40f);
  const auto rockLayer = size_t(DetailSurface::Rock);
  std::printf("dark green: rock detail %.3f without NDVI, %.3f at NDVI 0.08, %.3f at 0.40; grass %.3f / %.3f / %.3f\n",
              none[rockLayer], rock[rockLayer], plants[rockLayer], none[grass], rock[grass], plants[grass]);
  // Measured: grass 0.70 without NDVI, 0.06 at 0.08; rock 0.00 → 0.24.
  EXPECT_GT(none[grass], 0.5f);
  EXPECT_LT(rock[grass], 0.1f);
  EXPECT_GT(rock[rockLayer], 0.2f);
  EXPECT_LT(plants[rockLayer], 0.05f);
}

}  // namespace
}  // namespace vegstream::vegetation
