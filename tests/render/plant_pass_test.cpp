// The species pipelines (render/plant_pass.h) on lavapipe at 320 × 180: tessellated grass on a
// green field covers the near ground (sky untouched); a red-rock field grows gravel and no
// blades; pipeline statistics equal the analytic counts (patches = groups, evaluation
// invocations = plants × (segments + 1), geometry invocations and triangles = plants × segments
// × 2, doubled by the shadows); with MSAA 1 the alpha-test fallback draws the same plants.
// Validation stays silent with tessellation, geometry, alpha-to-coverage and shadows on.

#include <cstdio>

#include "plant_field.h"
#include "render/png_writer.h"

namespace vegstream::render::testing {
namespace {

class PlantPassTest : public GpuTest {};

// These tests are about the tessellation path (the renderer's default is the compute path,
// tests/render/blade_path_test.cpp compares the two).
PlantDrawOptions tessellation() {
  PlantDrawOptions d;
  d.path = BladePath::Tessellation;
  return d;
}

// Share of pixels in rows [y0, y1) the plants left as they were (the bare ground's colour, within
// 4 of 255): plants take their colour from that ground, so a small threshold.
double unchangedShare(const FieldResult& f, uint32_t y0, uint32_t y1) {
  const size_t changed = changedPixels(*f.with.color, *f.without.color, y0, y1, 4);
  return 1.0 - static_cast<double>(changed) / (static_cast<double>(kW) * (y1 - y0));
}

TEST_F(PlantPassTest, GrassCoversTheNearGroundOfAGreenFieldAndLeavesTheSky) {
  for (int msaa : {4, 1}) {
    auto r = makeRenderer(kW, kH, msaa);
    ASSERT_TRUE(r);
    ASSERT_TRUE(r->setImageryLayers(1).ok());
    const FieldResult f = renderField(*r, "grass", PlantStyle::Plants, tessellation(), {}, 120.0f);
    if (const char* dir = std::getenv("VEGSTREAM_TEST_PNG_DIR")) {  // for looking at the frames
      (void)writePng(std::string(dir) + "/grass_msaa" + std::to_string(msaa) + ".png", *f.with.color);
    }
    ASSERT_TRUE(f.with.vegetation.has_value());
    const int grass = speciesIndex("grass");
    EXPECT_GT(f.with.vegetation->plants[size_t(grass)], 20000u);
    // The seeded ground (from just under the horizon to mid-image) is mostly grass now.
    const double bare = unchangedShare(f, kH / 5, kH / 2);
    EXPECT_LT(bare, 0.5) << "MSAA " << msaa << ": share of the seeded ground still bare";
    std::printf("MSAA %d: %.1f %% of the seeded ground still bare\n", msaa, 100.0 * bare);
    EXPECT_EQ(changedPixels(*f.with.color, *f.without.color, 0, kH / 10), 0u) << "the sky is untouched";
    const PipelineStatistics& s = f.with.gpu.statistics;
    ASSERT_TRUE(s.available);
    EXPECT_GT(s.tessControlPatches, 0u);
    EXPECT_GT(s.geometryPrimitives, 0u);
  }
}

TEST_F(PlantPassTest, ARedRockFieldGrowsGravelAndNoBlades) {
  auto r = makeRenderer(kW, kH, 4);
  ASSERT_TRUE(r);
  ASSERT_TRUE(r->setImageryLayers(1).ok());
  const FieldResult f = renderField(*r, "red gravel", PlantStyle::Plants, tessellation());
  if (const char* dir = std::getenv("VEGSTREAM_TEST_PNG_DIR"))
    (void)writePng(std::string(dir) + "/gravel.png", *f.with.color);
  ASSERT_TRUE(f.with.vegetation.has_value());
  const VegetationFigures& v = *f.with.vegetation;
  const int gravel = speciesIndex("red gravel");
  EXPECT_GT(v.plants[size_t(gravel)], 0.99 * static_cast<double>(v.plantsTotal));
  EXPECT_EQ(v.plants[size_t(speciesIndex("grass"))], 0u);
  // Every patch is a gravel group: one line of one segment per stone, so the evaluation stage
  // ran at most twice per stone (culled groups run none) — no blade was tessellated.
  const PipelineStatistics& s = f.with.gpu.statistics;
  ASSERT_TRUE(s.available);
  EXPECT_EQ(s.tessControlPatches, v.groupsTotal);
  EXPECT_LE(s.tessEvaluationInvocations, 2 * v.plantsTotal);
  EXPECT_GT(s.tessEvaluationInvocations, 0u);
  // Stones are tinted by the ground they lie on: they change the image, but subtly.
  EXPECT_GT(changedPixels(*f.with.color, *f.without.color, kH / 5, kH / 2), 30u);
}

TEST_F(PlantPassTest, DryTuftsAreDrawnByTheFlowersPipeline) {
  // The third kind: catalog data (kind "flowers") plus one geometry shader.
  auto r = makeRenderer(kW, kH, 4);
  ASSERT_TRUE(r);
  ASSERT_TRUE(r->setImageryLayers(1).ok());
  const FieldResult f = renderField(*r, "dry tufts", PlantStyle::Plants, tessellation());
  ASSERT_TRUE(f.with.vegetation.has_value());
  const VegetationFigures& v = *f.with.vegetation;
  const int tufts = speciesIndex("dry tufts");
  ASSERT_GE(tufts, 0);
  EXPECT_EQ(vegetation::defaultSpeciesCatalog().species[size_t(tufts)].kind, vegetation::RendererKind::Flowers);
  EXPECT_GT(v.plants[size_t(tufts)], 0.9 * static_cast<double>(v.plantsTotal));
  EXPECT_GT(f.with.gpu.statistics.geometryPrimitives, 0u);
  EXPECT_GT(changedPixels(*f.with.color, *f.without.color, kH / 5, kH / 2, 4), 500u);
}

TEST_F(PlantPassTest, PipelineStatisticsEqualTheAnalyticCounts) {
  // Looking straight down from 120 m: every seed triangle in view, every blade at n_max segments.
  auto r = makeRenderer(kW, kH, 4);
  ASSERT_TRUE(r);
  ASSERT_TRUE(r->setImageryLayers(1).ok());
  for (int variant = 0; variant < 3; ++variant) {
    const bool shadows = variant == 1, speedOfLight = variant == 2;
    PlantDrawOptions draw = tessellation();
    draw.maxSegments = 4;
    draw.fullDetail = true;
    draw.shadows = shadows;
    draw.shadowDistanceM = 1000.0f;  // every plant's shadow (the field is 120 m below)
    draw.speedOfLight = speedOfLight;  // the same blades through the simplest shaders
    const FieldView top{{0.0, 33.0, 120.0}, {0.0, 0.0, -1.0}};
    const FieldResult f = renderField(*r, "grass", PlantStyle::Plants, draw, top, 24.0f);
    ASSERT_TRUE(f.with.vegetation.has_value());
    const VegetationFigures& v = *f.with.vegetation;
    const PipelineStatistics& s = f.with.gpu.statistics;
    ASSERT_TRUE(s.available);
    const uint64_t plants = v.plantsTotal, segments = draw.maxSegments, copies = shadows ? 2 : 1;
    ASSERT_GT(plants, 1000u);
    EXPECT_EQ(s.tessControlPatches, v.groupsTotal);
    EXPECT_EQ(s.tessEvaluationInvocations, plants * (segments + 1));
    // Two invocations per line segment (the second returns at once without shadows); some
    // drivers (lavapipe) count the instanced invocations of one primitive once.
    const uint64_t invocations = speedOfLight ? 1 : 2;
    EXPECT_TRUE(s.geometryInvocations == plants * segments * invocations || s.geometryInvocations == plants * segments)
        << s.geometryInvocations;
    EXPECT_EQ(s.geometryPrimitives, plants * segments * 2 * copies) << "shadows " << shadows;
    std::printf(
        "shadows %d, speed of light %d: %llu plants, %llu patches, %llu evaluation invocations, %llu geometry "
        "triangles\n",
        shadows ? 1 : 0, speedOfLight ? 1 : 0, static_cast<unsigned long long>(plants),
        static_cast<unsigned long long>(s.tessControlPatches),
        static_cast<unsigned long long>(s.tessEvaluationInvocations),
        static_cast<unsigned long long>(s.geometryPrimitives));
  }
}

}  // namespace
}  // namespace vegstream::render::testing
