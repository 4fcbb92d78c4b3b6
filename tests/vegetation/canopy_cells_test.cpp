// The crowns the plants thin under (vegetation/canopy_cells.h; issue 20 "grass thins under a
// crown"): the cover of one crown, the table's window and its toroidal addressing, and the
// classify's groups under a crown against the same ground without one.
#include <algorithm>
#include <cmath>
#include <set>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "vegetation/canopy_cells.h"
#include "vegetation/colour_score.h"
#include "vegetation/plant_seeding.h"
#include "vegetation/species_catalog.h"

namespace vegstream::vegetation {
namespace {

constexpr TreeGrid kGrid{7.0710678, 3.5};

TEST(CanopyCells, CoverIsOneUnderTheMiddleAndNoneOutsideTheCrown) {
  const glm::dvec3 camera{1003.7, -2051.2, 12.0};
  const glm::dvec3 tree = camera + glm::dvec3(10.3, -4.1, 0.0);
  // Another tree kCanopyCells cells east: the same slot of the table, out of its window.
  const glm::dvec3 far = tree + glm::dvec3(double(kCanopyCells) * kGrid.cellM, 0.0, 0.0);
  const std::vector<CanopyTree> trees = {{tree, 8.0f}, {far, 8.0f}};
  CanopyTable table;
  fillCanopyTable(kGrid, camera, trees, table);
  ASSERT_EQ(table.entries.size(), size_t{kCanopyCells} * kCanopyCells);
  const glm::vec2 c(10.3f, -4.1f);
  EXPECT_EQ(canopyCover(table, c), 1.0f);
  EXPECT_EQ(canopyCover(table, c + glm::vec2(0.59f * 4.0f, 0.0f)), 1.0f);
  const float edge = canopyCover(table, c + glm::vec2(0.0f, 0.8f * 4.0f));
  EXPECT_GT(edge, 0.2f);
  EXPECT_LT(edge, 0.8f);
  EXPECT_EQ(canopyCover(table, c + glm::vec2(-4.01f, 0.0f)), 0.0f);
  EXPECT_EQ(canopyCover(table, c + glm::vec2(3.0f, 3.0f)), 0.0f);  // 4.24 m away
  // The far tree is not in the table: its own place (the same slot) has no crown.
  EXPECT_EQ(canopyCover(table, glm::vec2(far - camera)), 0.0f);
  // An empty table covers nothing.
  EXPECT_EQ(canopyCover(CanopyTable{}, c), 0.0f);
}

// Six crowns of 12 m over a meadow (a 60 m triangle of grass, full detail): of the groups whose
// centre is within 0.6 of a crown's radius, 15 % ± 4 % are kept; beyond the crowns every group is
// the same as without them.
TEST(CanopyCells, GroupsUnderACrownThinToAboutFifteenPercent) {
  const SpeciesCatalog& catalog = defaultSpeciesCatalog();
  SeedTriangleInput t;
  t.key = 0x2468ace013579bdfull;
  t.vertices = {glm::dvec3(100, 100, 0), glm::dvec3(160, 100, 0), glm::dvec3(100, 160, 0)};
  t.plantCount = 60000.0f;
  // The ground the colour of the catalog's grass.
  glm::vec3 meadow{0.0f};
  for (const Species& s : catalog.species)
    if (s.name == "grass") meadow = s.score.reference;
  ASSERT_GT(meadow.y, 0.0f);
  const glm::vec3 srgb = srgbFromHsv(meadow);
  const GroundSample ground{{srgbDecode(srgb.r), srgbDecode(srgb.g), srgbDecode(srgb.b)}};  // no NDVI
  const BaseColourAt colour = [&](glm::vec2) { return ground; };
  const glm::dvec3 camera{90.0, 95.0, 2.0};
  const float radius = 6.0f;
  std::vector<CanopyTree> trees;
  for (const glm::dvec2 at : {glm::dvec2(112, 110), glm::dvec2(130, 112), glm::dvec2(112, 130), glm::dvec2(125, 125),
                              glm::dvec2(145, 108), glm::dvec2(108, 145)})
    trees.push_back({glm::dvec3(at, 0.0), 2.0f * radius});
  CanopyTable table;
  fillCanopyTable(kGrid, camera, trees, table);
  SeedingOptions bare{8}, under{8};
  under.canopy = &table;
  std::vector<PlantCluster> without, with;
  classifyTriangle(t, 0, catalog, bare, colour, without);
  classifyTriangle(t, 0, catalog, under, colour, with);
  ASSERT_GT(without.size(), 3000u);
  const auto distance = [&](const PlantCluster& g) {
    const glm::vec2 r = g.cluster == 0 ? seedPoint(t.key, 0, g.firstSeed) : clusterCentre(t.key, g.cluster);
    const glm::dvec3 p = t.vertices[0] + double(r.x) * (t.vertices[1] - t.vertices[0]) +
                         double(r.y) * (t.vertices[2] - t.vertices[0]);
    double nearest = 1e9;
    for (const CanopyTree& c : trees) nearest = std::min(nearest, std::hypot(p.x - c.position.x, p.y - c.position.y));
    return nearest;
  };
  using Key = std::tuple<uint32_t, uint32_t, uint32_t>;
  size_t innerWithout = 0, innerWith = 0;
  std::set<Key> outsideWithout, outsideWith;
  for (const PlantCluster& g : without) {
    if (distance(g) < 0.6 * radius) ++innerWithout;
    if (distance(g) > radius + 0.01) outsideWithout.insert({g.cluster, g.firstSeed, g.species});
  }
  for (const PlantCluster& g : with) {
    if (distance(g) < 0.6 * radius) ++innerWith;
    if (distance(g) > radius + 0.01) outsideWith.insert({g.cluster, g.firstSeed, g.species});
  }
  const double kept = double(innerWith) / double(innerWithout);
  std::printf("under the crown's middle: %zu of %zu groups kept (%.1f %%); %zu groups outside it, the same\n",
              innerWith, innerWithout, 100.0 * kept, outsideWith.size());
  ASSERT_GT(innerWithout, 800u);
  EXPECT_NEAR(kept, 1.0 - kCanopyThinning, 0.04);
  EXPECT_EQ(outsideWith, outsideWithout);
}

}  // namespace
}  // namespace vegstream::vegetation
