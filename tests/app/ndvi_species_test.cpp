// The default catalog's NDVI channel on the real Zion sample (issue 18, item 4), imported with the
// display stretch its references were read from (zionStretchedSample; the default import's
// de-shaded albedo has almost no dark shadowed rock left, 548 pixels): over every pixel of the
// max-zoom tiles, the species the colour alone picks against the one colour + NDVI
// picks. Dark pixels whose NDVI says bare rock (v < 0.15, NDVI < 0.2: canyon walls in shadow)
// must mostly stop growing grass and forest, while dark pixels whose NDVI says vegetation
// (≥ 0.3: the plateau forest) keep growing plants.

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "datasets/dataset_reader.h"
#include "tests/support/zion_sample.h"
#include "vegetation/colour_score.h"
#include "vegetation/species_catalog.h"
#include "vegetation/species_choice.h"

namespace vegstream::testing {
namespace {

namespace fs = std::filesystem;
namespace veg = vegstream::vegetation;

struct Shares {
  uint64_t pixels = 0, plantsByColour = 0, plantsWithNdvi = 0;
};

TEST(DefaultCatalogNdvi, ShadowedRockStopsGrowingForestWhileTheForestKeepsIt) {
  const auto dataset = zionStretchedSample();
  ASSERT_TRUE(dataset.ok()) << dataset.error().message;
  auto reader = datasets::DatasetReader::open(*dataset);
  ASSERT_TRUE(reader.ok()) << reader.error().message;
  ASSERT_TRUE(reader->meta().ndvi) << "the sample fixture imports band 5";
  const veg::SpeciesCatalog& catalog = veg::defaultSpeciesCatalog();
  // Grass and forest: what shadowed rock must not grow (gravel and dry tufts may be on rock).
  const auto grows = [&](int s) {
    if (s < 0 || catalog.species[size_t(s)].bare) return false;
    const veg::RendererKind k = catalog.species[size_t(s)].kind;
    return k == veg::RendererKind::Grass || k == veg::RendererKind::Tree;
  };

  Shares shadowedRock, darkVegetation;
  const int z = reader->meta().maxZoom;
  for (const auto& x : fs::directory_iterator(*dataset / "imagery" / std::to_string(z)))
    for (const auto& y : fs::directory_iterator(x.path())) {
      const geo::TileId id{z, std::stoi(x.path().filename().string()), std::stoi(y.path().stem().string())};
      auto tile = reader->colorTile(id);
      ASSERT_TRUE(tile.ok()) << tile.error().message;
      const datasets::ColorTile& t = **tile;
      if (t.ndvi.empty()) continue;
      for (size_t i = 0; i < t.ndvi.size(); ++i) {
        const uint8_t* p = &t.rgba[i * 4];
        if (p[3] == 0 || t.ndvi[i] == 0) continue;
        const glm::vec3 hsv = veg::hsvFromSrgb8(p[0], p[1], p[2]);
        const float ndvi = datasets::ndviFromByte(t.ndvi[i]);
        if (hsv.z >= 0.15f) continue;
        Shares* s = ndvi < 0.2f ? &shadowedRock : ndvi >= 0.3f ? &darkVegetation : nullptr;
        if (!s) continue;
        ++s->pixels;
        s->plantsByColour += grows(veg::speciesCandidates(catalog, hsv).first) ? 1 : 0;
        s->plantsWithNdvi += grows(veg::speciesCandidates(catalog, hsv, ndvi).first) ? 1 : 0;
      }
    }
  const auto share = [](uint64_t n, const Shares& s) { return double(n) / double(s.pixels); };
  std::printf("dark pixels growing grass or forest (best species): shadowed rock (NDVI < 0.2, %llu px) %.3f by colour, %.3f "
              "with NDVI; vegetation (NDVI >= 0.3, %llu px) %.3f by colour, %.3f with NDVI\n",
              static_cast<unsigned long long>(shadowedRock.pixels), share(shadowedRock.plantsByColour, shadowedRock),
              share(shadowedRock.plantsWithNdvi, shadowedRock), static_cast<unsigned long long>(darkVegetation.pixels),
              share(darkVegetation.plantsByColour, darkVegetation), share(darkVegetation.plantsWithNdvi, darkVegetation));
  ASSERT_GT(shadowedRock.pixels, 10000u);
  ASSERT_GT(darkVegetation.pixels, 10000u);
  // Measured: 0.23 → 0.08 (rock), 0.96 → 0.99 (vegetation).
  EXPECT_GT(share(shadowedRock.plantsByColour, shadowedRock), 0.12) << "the case NDVI is for exists";
  EXPECT_LT(share(shadowedRock.plantsWithNdvi, shadowedRock), 0.5 * share(shadowedRock.plantsByColour, shadowedRock));
  EXPECT_GT(share(darkVegetation.plantsWithNdvi, darkVegetation), 0.95);
}

}  // namespace
}  // namespace vegstream::testing
