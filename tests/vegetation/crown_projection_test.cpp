// vegetation/crown_projection.h: the radius of the disk of a mesh's area seen from above — exact
// for shapes whose area is known, overlaps counted once, height ignored; and for the catalog's
// trees, a crown area radius below the widest reach (the ground between a conifer's branches).
// The exact shapes are sampled on a 512-cell grid: on the default 128 a 0.5 m bar over a 6 m reach
// is 10 or 11 cells wide, a 5 % error in its area.

#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "vegetation/crown_projection.h"
#include "vegetation/species_catalog.h"
#include "vegetation/tree_model.h"

namespace vegstream::vegetation {
namespace {

constexpr float kPi = 3.14159265f;

void addQuad(TreeMesh& m, float x0, float y0, float x1, float y1, float z) {
  const auto base = static_cast<uint32_t>(m.vertices.size());
  for (const auto& [x, y] : {std::pair{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}) {
    TreeVertex v{};
    v.position[0] = x, v.position[1] = y, v.position[2] = z;
    m.vertices.push_back(v);
  }
  for (uint32_t k : {0u, 1u, 2u, 0u, 2u, 3u}) m.indices.push_back(base + k);
}

float discRadius(float area) { return std::sqrt(area / kPi); }

TEST(CrownProjection, ASquareHasItsArea) {
  TreeMesh m;
  addQuad(m, -2.0f, -2.0f, 2.0f, 2.0f, 5.0f);
  EXPECT_NEAR(crownProjectionRadius(m, 512), discRadius(16.0f), 0.01f);
}

TEST(CrownProjection, OverlapsCountOnceAndHeightDoesNotMatter) {
  TreeMesh m;
  addQuad(m, -3.0f, -1.0f, 1.0f, 1.0f, 2.0f);  // 8 m²
  addQuad(m, -1.0f, -1.0f, 3.0f, 1.0f, 9.0f);  // 8 m², 4 of them over the first
  EXPECT_NEAR(crownProjectionRadius(m, 512), discRadius(12.0f), 0.02f);
}

TEST(CrownProjection, ACrossCoversLessThanItsReach) {
  TreeMesh m;  // two 6 × 0.5 m bars crossing: 5.75 m² within a reach of 3 m
  addQuad(m, -3.0f, -0.25f, 3.0f, 0.25f, 1.0f);
  addQuad(m, -0.25f, -3.0f, 0.25f, 3.0f, 1.0f);
  EXPECT_NEAR(crownProjectionRadius(m, 512), discRadius(5.75f), 0.03f);
  EXPECT_EQ(crownProjectionRadius(TreeMesh{}), 0.0f);
}

TEST(CrownProjection, CatalogTreesCoverBetweenAThirdAndAllOfTheirReach) {
  for (const Species& s : defaultSpeciesCatalog().species) {
    if (!isTree(s)) continue;
    const TreeModel model =
        buildTreeModel(s.tree, 0.5f * (s.heightM.min + s.heightM.max), 0.5f * (s.widthM.min + s.widthM.max), 7u);
    const float area = kPi * model.crownAreaRadiusM * model.crownAreaRadiusM;
    const float disc = kPi * model.crownRadiusM * model.crownRadiusM;
    std::printf("%-16s reach %.2f m, area radius %.2f m: %.0f %% of the disc\n", s.name.c_str(), model.crownRadiusM,
                model.crownAreaRadiusM, 100.0f * area / disc);
    EXPECT_GT(area, disc / 3.0f) << s.name;
    EXPECT_LT(model.crownAreaRadiusM, model.crownRadiusM) << s.name;
    EXPECT_EQ(model.crownAreaRadiusM, crownProjectionRadius(model.lod[0])) << s.name;
  }
}

}  // namespace
}  // namespace vegstream::vegetation
