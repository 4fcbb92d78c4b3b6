// The default terrain-type table: sane entries, and the colour score picks the type a person
// would for typical imagery colours of the samples (8-bit sRGB as imported).

#include "vegetation/terrain_types.h"

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
  std::set<std::string_view> names;
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
  for (const char* want : {"meadow", "forest", "red rock", "gravel", "pale sandstone", "grey rock"})
    EXPECT_TRUE(names.count(want)) << want;
}

// Colours read off the imported Zion sample (10 × 10 pixel means) and typical aerial photos.
TEST(TerrainTypes, TypicalImageryColoursPickTheirType) {
  EXPECT_EQ(pick(104, 120, 60), "meadow");           // a bright clearing
  EXPECT_EQ(pick(92, 122, 52), "meadow");            // Goleta lawn
  EXPECT_EQ(pick(36, 42, 25), "forest");             // Zion plateau forest
  EXPECT_EQ(pick(33, 38, 25), "forest");             // forest in shadow
  EXPECT_EQ(pick(149, 101, 88), "red rock");         // Zion red sandstone (Kolob)
  EXPECT_EQ(pick(172, 92, 62), "red rock");          // a more saturated red wall
  EXPECT_EQ(pick(106, 86, 77), "gravel");            // Zion desert floor
  EXPECT_EQ(pick(78, 58, 50), "gravel");             // darker brown scree
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
  EXPECT_GT(surfaceWeights(types, hsvFromSrgb8(149, 101, 88))[size_t(DetailSurface::Rock)], 0.6f);
  // A colour halfway (in HSV) between meadow and forest has a good share of both.
  ASSERT_EQ(types[0].name, "meadow");
  ASSERT_EQ(types[1].name, "forest");
  const auto between = terrainTypeWeights(types, 0.5f * (types[0].score.reference + types[1].score.reference));
  EXPECT_GT(between[0], 0.25f);
  EXPECT_GT(between[1], 0.25f);
  EXPECT_GT(between[0] + between[1], 0.8f);
}

}  // namespace
}  // namespace vegstream::vegetation
