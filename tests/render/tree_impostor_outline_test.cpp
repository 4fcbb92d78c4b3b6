// The impostors' triangle (render/tree_impostor_outline.h): every vertex of every tree model of
// the default catalog that the rectangle used to show, seen at any yaw and elevation, lies inside
// the triangle the vertex stage draws; a conifer's triangle is smaller than the rectangle. No GPU.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "render/tree_impostor_outline.h"
#include "vegetation/species_catalog.h"
#include "vegetation/tree_model.h"

namespace vegstream::render {
namespace {

TEST(ImpostorTriangle, HoldsEveryVertexOfEveryModelAtAnyYawAndElevation) {
  int models = 0;
  for (const vegetation::Species& sp : vegetation::defaultSpeciesCatalog().species) {
    if (!vegetation::isTree(sp)) continue;
    const vegetation::TreeModel model = vegetation::buildTreeModel(sp.tree, 15.0f, 6.0f, 11u);
    float radius = 0.0f;
    const float centreZ = 0.5f * model.modelHeightM;
    for (const auto& v : model.lod[0].vertices)
      radius = std::max(radius, std::hypot(std::hypot(v.position[0], v.position[1]), v.position[2] - centreZ));
    const ImpostorQuadShape q{model.modelHeightM, std::max(model.crownRadiusM, 0.1f), 1.02f * radius, centreZ};
    const ImpostorTriangle t = impostorTriangle(model.lod[0].vertices, q);
    ++models;
    for (int bin = 0; bin < 4; ++bin) {
      // Area against the rectangle's (2 × 1 in these units).
      const float area = t.apex[bin] * t.base[bin] / 2.0f;
      std::printf("%s, sin(elevation) bin %d: apex at %.2f of the height, base ±%.2f of the width: %.0f %% of the "
                  "rectangle's area\n",
                  sp.name.c_str(), bin, t.apex[bin], t.base[bin], 100.0 * area);
      EXPECT_GE(t.apex[bin], 1.0f);
      // Off the sampled elevations and yaws: every vertex inside (the margin covers the sampling).
      for (int e = 0; e < 7; ++e) {
        const float sinE = std::min(0.999f, 0.25f * (float(bin) + (float(e) + 0.37f) / 7.0f));
        const float cosE = std::sqrt(1.0f - sinE * sinE);
        const glm::vec2 half = impostorQuadHalf(q, sinE);
        int outside = 0;
        for (const auto& v : model.lod[0].vertices) {
          const float rho = std::hypot(v.position[0], v.position[1]);
          for (int a = 0; a < 97; ++a) {
            const float phi = 6.2831853f * float(a) / 97.0f + 0.11f;
            const float x = std::abs(rho * std::cos(phi));
            const float y = (v.position[2] - centreZ) * cosE - rho * std::sin(phi) * sinE;
            if (std::abs(y) >= half.y || x >= half.x) continue;  // outside the rectangle: never drawn
            if (x > impostorTriangleWidth(t, bin, (y + half.y) / (2.0f * half.y)) * half.x + 1e-4f) ++outside;
          }
        }
        EXPECT_EQ(outside, 0) << sp.name << " at sin(elevation) " << sinE;
      }
    }
    if (sp.tree.form == vegetation::TreeForm::Conifer) {  // seen from the side: a cone in a triangle
      EXPECT_LT(t.apex[0] * t.base[0] / 2.0f, 0.9f) << sp.name;
    }
  }
  EXPECT_GT(models, 1);
}

}  // namespace
}  // namespace vegstream::render
