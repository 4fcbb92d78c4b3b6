// The two blade paths (render/plant_pass.h: tessellation; render/blade_pass.h: compute) on
// lavapipe at 320 × 180 draw the same plants: the same classify figures; the compute path writes
// exactly the triangles the geometry stages emit (grass, gravel, flower kinds, with and without
// shadows); the clipper sees the same primitives; the rest of the pipeline statistics differ only
// as the paths do (patches and tessellation/geometry work against indexed triangles and vertex
// invocations); the images differ only at blade edges, with MSAA 4 and 1; each path is
// deterministic; both end the planar shadows at the same distance and lean phototropic blades
// towards the sun; the buffers follow the eq. 4
// bound, and plants past a ceiling are dropped whole
// and counted; the validation layers stay silent (GpuTest). RendererOptions: auto resolves to
// compute, mesh is refused naming the option and the device.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "plant_field.h"
#include "render/blade_pass.h"
#include "render/png_writer.h"
#include "vegetation/species_catalog.h"

namespace vegstream::render::testing {
namespace {

class BladePathTest : public GpuTest {};

PlantDrawOptions withPath(PlantDrawOptions d, BladePath path) {
  d.path = path;
  return d;
}

void savePng(const std::string& name, const ColorImage& img) {
  if (const char* dir = std::getenv("VEGSTREAM_TEST_PNG_DIR")) (void)writePng(std::string(dir) + "/" + name, img);
}

// Pixels of the whole frame that differ by more than `threshold` in any channel.
size_t differing(const ColorImage& a, const ColorImage& b, int threshold) {
  return changedPixels(a, b, 0, a.height, threshold);
}

// Pixels `subset` changes clearly (> 10 from `bare`) where `superset` leaves the bare field as it
// was (within 4) in the pixel and its 8 neighbours.
size_t strayPixels(const ColorImage& subset, const ColorImage& superset, const ColorImage& bare) {
  auto diff = [&](const ColorImage& img, int x, int y) {
    const size_t i = (size_t(y) * img.width + size_t(x)) * 4;
    int d = 0;
    for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(int(img.rgba[i + c]) - int(bare.rgba[i + c])));
    return d;
  };
  size_t n = 0;
  for (int y = 0; y < int(bare.height); ++y)
    for (int x = 0; x < int(bare.width); ++x) {
      if (diff(subset, x, y) <= 10) continue;
      bool plant = false;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          plant = plant || diff(superset, std::clamp(x + dx, 0, int(bare.width) - 1),
                                std::clamp(y + dy, 0, int(bare.height) - 1)) > 4;
      if (!plant) ++n;
    }
  return n;
}

// Plant pixels either frame has where the other has none nearby: blades in different places.
size_t misplacedPlantPixels(const ColorImage& a, const ColorImage& b, const ColorImage& bare) {
  return strayPixels(a, b, bare) + strayPixels(b, a, bare);
}

TEST_F(BladePathTest, BothPathsDrawTheSameGrassAndImagesDifferOnlyAtBladeEdges) {
  auto r = makeRenderer(kW, kH, 4);
  ASSERT_TRUE(r);
  ASSERT_TRUE(r->setImageryLayers(1).ok());
  EXPECT_EQ(r->bladePath(), BladePath::Compute) << "auto picks compute";
  const PlantDrawOptions draw;  // the defaults: eq. 4 LOD, shadows on
  const FieldResult tess = renderField(*r, "grass", PlantStyle::Plants, withPath(draw, BladePath::Tessellation));
  const FieldResult comp = renderField(*r, "grass", PlantStyle::Plants, withPath(draw, BladePath::Compute));
  savePng("paths_tessellation.png", *tess.with.color);
  savePng("paths_compute.png", *comp.with.color);
  ASSERT_TRUE(tess.with.vegetation && comp.with.vegetation);
  const VegetationFigures &vt = *tess.with.vegetation, &vc = *comp.with.vegetation;
  EXPECT_EQ(vt.plants, vc.plants) << "the same classify figures";
  EXPECT_EQ(vt.groups, vc.groups);
  EXPECT_GT(vc.plantsTotal, 20000u);
  EXPECT_FALSE(vt.bladeCounts) << "the tessellation path has no expansion counters";
  ASSERT_TRUE(vc.bladeCounts);
  EXPECT_EQ(vc.bladesDropped, 0u);

  const PipelineStatistics &st = tess.with.gpu.statistics, &sc = comp.with.gpu.statistics;
  ASSERT_TRUE(st.available && sc.available);
  // The compute path wrote exactly the triangles the geometry stages emitted.
  EXPECT_GT(st.geometryPrimitives, vc.plantsTotal);
  EXPECT_EQ(vc.bladeTriangles, st.geometryPrimitives);
  // No tessellation or geometry work in the compute path; its blades are input primitives
  // instead of one patch per group; the clipper sees the same primitives either way.
  EXPECT_EQ(sc.tessControlPatches, 0u);
  EXPECT_EQ(sc.tessEvaluationInvocations, 0u);
  EXPECT_EQ(sc.geometryPrimitives, 0u);
  EXPECT_EQ(st.tessControlPatches, vt.groupsTotal);
  EXPECT_EQ(sc.inputPrimitives - vc.bladeTriangles, st.inputPrimitives - st.tessControlPatches);
  EXPECT_EQ(sc.clippingInvocations, st.clippingInvocations);
  EXPECT_GT(sc.computeInvocations, st.computeInvocations) << "the expansion runs in compute";
  // Rasterised coverage agrees to float rounding at edges.
  const double fragRatio = double(sc.fragmentInvocations) / double(st.fragmentInvocations);
  EXPECT_NEAR(fragRatio, 1.0, 0.01);

  // Images: the same plants in the same places, shaded alike; vertices equal up to float
  // rounding move a few edge pixels.
  const ColorImage &a = *tess.with.color, &b = *comp.with.color;
  const double pixels = double(kW) * kH;
  const size_t big = differing(a, b, 24), any = differing(a, b, 4);
  const size_t plantPixels = changedPixels(a, *tess.without.color, 0, kH, 4);
  std::printf(
      "%zu plant pixels; differing pixels: %zu by > 4, %zu by > 24 (of %.0f); plant pixels in one frame only %zu\n",
      plantPixels, any, big, pixels, misplacedPlantPixels(a, b, *tess.without.color));
  ASSERT_GT(plantPixels, size_t(0.1 * pixels)) << "the grass covers the near ground";
  EXPECT_LT(double(big), 0.02 * pixels);
  EXPECT_GT(1.0 - double(any) / pixels, 0.95) << "share of pixels that match within 4";
  EXPECT_EQ(misplacedPlantPixels(a, b, *tess.without.color), 0u) << "differences only at blades";
  // (The default grass grows on dark olive imagery, v 0.2: its blades stand out less.)
  EXPECT_GT(misplacedPlantPixels(a, *tess.without.color, *tess.without.color), size_t(0.015 * pixels))
      << "the check sees plants that are not in the other frame";
}

TEST_F(BladePathTest, ComputeTrianglesEqualTheGeometryStagesForEveryKindWithAndWithoutShadows) {
  auto r = makeRenderer(kW, kH, 4);
  ASSERT_TRUE(r);
  ASSERT_TRUE(r->setImageryLayers(1).ok());
  for (const char* species : {"grass", "red gravel", "dry tufts"})
    for (bool shadows : {true, false}) {
      SCOPED_TRACE(std::string(species) + (shadows ? ", shadows" : ", no shadows"));
      PlantDrawOptions draw;
      draw.shadows = shadows;
      draw.maxSegments = 4;
      const FieldResult t =
          renderField(*r, species, PlantStyle::Plants, withPath(draw, BladePath::Tessellation), {}, 24.0f);
      const FieldResult c = renderField(*r, species, PlantStyle::Plants, withPath(draw, BladePath::Compute), {}, 24.0f);
      ASSERT_TRUE(t.with.vegetation && c.with.vegetation);
      EXPECT_EQ(t.with.vegetation->plants, c.with.vegetation->plants);
      ASSERT_GT(t.with.gpu.statistics.geometryPrimitives, 0u);
      EXPECT_EQ(c.with.vegetation->bladeTriangles, t.with.gpu.statistics.geometryPrimitives);
      EXPECT_EQ(c.with.gpu.statistics.clippingInvocations, t.with.gpu.statistics.clippingInvocations);
      EXPECT_LT(double(differing(*t.with.color, *c.with.color, 24)), 0.02 * kW * kH);
      EXPECT_EQ(misplacedPlantPixels(*t.with.color, *c.with.color, *t.without.color), 0u);
      EXPECT_GT(changedPixels(*c.with.color, *c.without.color, 0, kH, 4), 100u) << "the plants are drawn";
      const std::string name = std::string(species) + (shadows ? "" : "_noshadow");
      savePng("kind_" + name + "_tessellation.png", *t.with.color);
      savePng("kind_" + name + "_compute.png", *c.with.color);
    }
}

TEST_F(BladePathTest, ASpeciesWithoutShadowsCastsNoneOnEitherPath) {
  // config/species.json: the dense grass casts no planar shadows (its blades cover the ground),
  // the sparse red gravel does. Shadow triangles are counted on both paths.
  auto r = makeRenderer(kW, kH, 4);
  ASSERT_TRUE(r);
  ASSERT_TRUE(r->setImageryLayers(1).ok());
  ASSERT_TRUE(r->setSpeciesCatalog(vegetation::defaultSpeciesCatalog()).ok());
  PlantDrawOptions draw;
  draw.maxSegments = 4;
  for (const char* species : {"grass", "red gravel"}) {
    SCOPED_TRACE(species);
    draw.shadows = false;
    const FieldResult without = renderField(*r, species, PlantStyle::Plants, withPath(draw, BladePath::Compute), {}, 24.0f);
    draw.shadows = true;
    const FieldResult c = renderField(*r, species, PlantStyle::Plants, withPath(draw, BladePath::Compute), {}, 24.0f);
    const FieldResult t = renderField(*r, species, PlantStyle::Plants, withPath(draw, BladePath::Tessellation), {}, 24.0f);
    ASSERT_TRUE(without.with.vegetation && c.with.vegetation && t.with.vegetation);
    ASSERT_GT(without.with.vegetation->plantsTotal, 0u);
    const uint64_t shadowTriangles = c.with.vegetation->bladeTriangles - without.with.vegetation->bladeTriangles;
    EXPECT_EQ(c.with.vegetation->bladeTriangles, t.with.gpu.statistics.geometryPrimitives);
    if (std::string(species) == "grass")
      EXPECT_EQ(shadowTriangles, 0u);
    else
      EXPECT_GT(shadowTriangles, 0u);
  }
}

TEST_F(BladePathTest, ShadowsEndAtTheShadowDistanceOnBothPaths) {
  // PlantDrawOptions::shadowDistanceM: a seed triangle's plants cast shadows only while its
  // bounding sphere reaches inside the distance, decided alike on both paths (the same triangles);
  // the shadow triangles grow with the distance, none within 1 m of a camera 2 m up, every one at
  // 1 km (a flat field: every group casts), and shadows change pixels only when they exist.
  auto r = makeRenderer(kW, kH, 4);
  ASSERT_TRUE(r);
  ASSERT_TRUE(r->setImageryLayers(1).ok());
  PlantDrawOptions draw;
  draw.maxSegments = 4;
  draw.shadows = false;
  const FieldResult bare = renderField(*r, "grass", PlantStyle::Plants, withPath(draw, BladePath::Compute), {}, 24.0f);
  ASSERT_TRUE(bare.with.vegetation);
  const uint64_t plantTriangles = bare.with.vegetation->bladeTriangles;
  ASSERT_GT(plantTriangles, 0u);
  draw.shadows = true;
  std::vector<uint64_t> shadowTriangles;
  for (float distance : {1.0f, 6.0f, 12.0f, 1000.0f}) {
    SCOPED_TRACE("shadow distance " + std::to_string(distance));
    draw.shadowDistanceM = distance;
    const FieldResult t =
        renderField(*r, "grass", PlantStyle::Plants, withPath(draw, BladePath::Tessellation), {}, 24.0f);
    const FieldResult c = renderField(*r, "grass", PlantStyle::Plants, withPath(draw, BladePath::Compute), {}, 24.0f);
    ASSERT_TRUE(t.with.vegetation && c.with.vegetation);
    EXPECT_EQ(c.with.vegetation->bladeTriangles, t.with.gpu.statistics.geometryPrimitives);
    EXPECT_EQ(c.with.vegetation->plants, bare.with.vegetation->plants);
    shadowTriangles.push_back(c.with.vegetation->bladeTriangles - plantTriangles);
    if (shadowTriangles.back() == 0) {
      EXPECT_EQ(differing(*c.with.color, *bare.with.color, 0), 0u) << "no shadow, no change";
    } else if (distance >= 12.0f) {  // (at 6 m the few shadows are still fading in)
      // The grass's ground is dark olive (v 0.2): a 35 % shadow takes 5–15 levels off it.
      EXPECT_GT(differing(*c.with.color, *bare.with.color, 4), 50u) << "the shadows darken the ground";
    }
  }
  EXPECT_EQ(shadowTriangles[0], 0u);
  EXPECT_LT(shadowTriangles[0], shadowTriangles[1]);
  EXPECT_LT(shadowTriangles[1], shadowTriangles[2]);
  EXPECT_LT(shadowTriangles[2], shadowTriangles[3]);
  EXPECT_EQ(shadowTriangles[3], plantTriangles);
}

// Plant pixels (differing from the bare field by more than 3: blades take the ground's colour)
// whose up-right neighbour is one too, and those whose up-left one is: blades leaning right on
// screen make more of the first.
std::pair<size_t, size_t> diagonalPairs(const ColorImage& with, const ColorImage& bare) {
  auto plant = [&](uint32_t x, uint32_t y) {
    const size_t i = (size_t(y) * with.width + x) * 4;
    int d = 0;
    for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(int(with.rgba[i + c]) - int(bare.rgba[i + c])));
    return d > 3;
  };
  size_t right = 0, left = 0;
  for (uint32_t y = 1; y < with.height; ++y)
    for (uint32_t x = 1; x + 1 < with.width; ++x) {
      if (!plant(x, y)) continue;
      right += plant(x + 1, y - 1) ? 1 : 0;
      left += plant(x - 1, y - 1) ? 1 : 0;
    }
  return {right, left};
}

TEST_F(BladePathTest, PhototropicBladesLeanTowardsTheSunOnBothPaths) {
  // Issue 18: phototropism 1 turns every grass blade towards the sun's azimuth (seed 001 §2.3;
  // plants grow towards light). Looking north over the field with a low sun in the east, blades
  // lean right on screen (more plant pixels continue up-right than up-left); with the sun in the
  // west, left. No shadows, so only the blades make the pixels.
  vegetation::SpeciesCatalog catalog = vegetation::defaultSpeciesCatalog();
  for (vegetation::Species& sp : catalog.species)
    if (sp.name == "grass") {
      sp.phototropism = 1.0f;
      sp.stiffness = {0.7f, 0.8f};  // soft (in k_c): the blades bend well over, so the lean shows
      // Short and narrow, so neighbours rarely touch and each blade's direction is measured
      // (independent of the shipped catalog's tuning).
      sp.heightM = {0.2f, 0.55f};
      sp.widthM = {0.012f, 0.03f};
      sp.colourModulation = {0.85f, 1.15f};
    }
  auto r = makeRenderer(kW, kH, 4);
  ASSERT_TRUE(r);
  ASSERT_TRUE(r->setImageryLayers(1).ok());
  ASSERT_TRUE(r->setSpeciesCatalog(catalog).ok());
  PlantDrawOptions draw;
  draw.shadows = false;
  for (BladePath path : {BladePath::Tessellation, BladePath::Compute}) {
    SCOPED_TRACE(bladePathName(path));
    FieldView east, west;
    east.sun = {1.0, 0.0, 0.35};
    west.sun = {-1.0, 0.0, 0.35};
    const FieldResult e = renderField(*r, "grass", PlantStyle::Plants, withPath(draw, path), east);
    const FieldResult w = renderField(*r, "grass", PlantStyle::Plants, withPath(draw, path), west);
    const auto [eRight, eLeft] = diagonalPairs(*e.with.color, *e.without.color);
    const auto [wRight, wLeft] = diagonalPairs(*w.with.color, *w.without.color);
    std::printf("%s: sun east %zu right / %zu left, sun west %zu right / %zu left\n", bladePathName(path), eRight,
                eLeft, wRight, wLeft);
    EXPECT_GT(eLeft, 100u);
    // Which blade pixels differ from the bare ground depends on their lighting too (issue 39: the
    // blades take the ground's albedo, so only their shading tells them apart): each sun's lean
    // shows, and the lean flips with the sun.
    EXPECT_GT(double(eRight), 1.15 * double(eLeft)) << "sun in the east: blades lean east (right)";
    EXPECT_GT(double(wLeft), 1.3 * double(wRight)) << "sun in the west: blades lean west (left)";
    EXPECT_GT(double(eRight) / double(eLeft), 1.5 * double(wRight) / double(wLeft)) << "the lean flips with the sun";
  }
}

TEST_F(BladePathTest, WithoutMsaaBothPathsTakeTheSameAlphaTest) {
  // MSAA 1: the fragment stage's computed coverage becomes an alpha test with the same dither.
  auto r = makeRenderer(kW, kH, 1);
  ASSERT_TRUE(r);
  ASSERT_TRUE(r->setImageryLayers(1).ok());
  const FieldResult t = renderField(*r, "grass", PlantStyle::Plants, withPath({}, BladePath::Tessellation));
  const FieldResult c = renderField(*r, "grass", PlantStyle::Plants, withPath({}, BladePath::Compute));
  ASSERT_TRUE(t.with.vegetation && c.with.vegetation);
  EXPECT_EQ(c.with.vegetation->bladeTriangles, t.with.gpu.statistics.geometryPrimitives);
  EXPECT_GT(changedPixels(*c.with.color, *c.without.color, 0, kH, 4), size_t(0.1 * kW * kH));
  EXPECT_LT(double(differing(*t.with.color, *c.with.color, 24)), 0.02 * kW * kH);
  EXPECT_EQ(misplacedPlantPixels(*t.with.color, *c.with.color, *t.without.color), 0u);
  savePng("msaa1_compute.png", *c.with.color);
}

TEST_F(BladePathTest, LookingDownTheComputePathWritesTheAnalyticCounts) {
  // Every seed triangle in view, every blade at n_max segments: 2 triangles per segment per blade,
  // doubled by the shadows; vertices 2 (n + 1) per blade, doubled too.
  auto r = makeRenderer(kW, kH, 4);
  ASSERT_TRUE(r);
  ASSERT_TRUE(r->setImageryLayers(1).ok());
  PlantDrawOptions draw;
  draw.maxSegments = 4;
  draw.fullDetail = true;
  draw.shadowDistanceM = 1000.0f;  // every plant's shadow (the field is 120 m below)
  draw.path = BladePath::Compute;
  const FieldView top{{0.0, 33.0, 120.0}, {0.0, 0.0, -1.0}};
  const FieldResult f = renderField(*r, "grass", PlantStyle::Plants, draw, top, 24.0f);
  ASSERT_TRUE(f.with.vegetation);
  const VegetationFigures& v = *f.with.vegetation;
  ASSERT_GT(v.plantsTotal, 1000u);
  EXPECT_EQ(v.bladeTriangles, v.plantsTotal * 4 * 2 * 2);
  EXPECT_EQ(v.bladeVertices, v.plantsTotal * 2 * (4 + 1) * 2);
  EXPECT_EQ(f.with.gpu.statistics.inputVertices, f.without.gpu.statistics.inputVertices + 3 * v.bladeTriangles);
}

TEST_F(BladePathTest, TheBuffersFollowTheFramesLodBoundAndNothingIsDropped) {
  // The expansion's buffers are sized by the CPU's bound at each triangle's eq. 4 segments: a
  // full-detail frame of the same field needs (and gets) more than a level-of-detail one.
  auto r = makeRenderer(kW, kH, 4);
  ASSERT_TRUE(r);
  ASSERT_TRUE(r->setImageryLayers(1).ok());
  PlantDrawOptions draw = withPath({}, BladePath::Compute);
  draw.maxSegments = 8;
  const uint64_t before = r->gpuBytes();
  const FieldResult lod = renderField(*r, "grass", PlantStyle::Plants, draw);
  const uint64_t withLod = r->gpuBytes();
  draw.fullDetail = true;
  const FieldResult full = renderField(*r, "grass", PlantStyle::Plants, draw);
  const uint64_t withFull = r->gpuBytes();
  ASSERT_TRUE(lod.with.vegetation && full.with.vegetation);
  EXPECT_EQ(lod.with.vegetation->bladesDropped, 0u);
  EXPECT_EQ(full.with.vegetation->bladesDropped, 0u);
  EXPECT_GT(full.with.vegetation->bladeTriangles, lod.with.vegetation->bladeTriangles);
  EXPECT_GT(withLod, before);
  EXPECT_GT(withFull, withLod) << "full detail needs larger buffers than eq. 4's level of detail";
}

TEST(BladeBufferStart, FullWhereTheCeilingsAreASixteenthOfTheDeviceHalfOnSmallerGpusSmallOnACpu) {
  constexpr uint64_t kGiB = 1ull << 30;
  const uint64_t ceilings = 3 * (256ull << 20) + 3 * (96ull << 20);  // three slots at the default ceiling: 1.03 GiB
  EXPECT_EQ(chooseBladeBufferStart(false, 141 * kGiB, ceilings), BladeBufferStart::Full);  // an H200
  EXPECT_EQ(chooseBladeBufferStart(false, 16 * kGiB + 512 * (1ull << 20), ceilings), BladeBufferStart::Full);
  EXPECT_EQ(chooseBladeBufferStart(false, 16 * kGiB, ceilings), BladeBufferStart::Half);
  EXPECT_EQ(chooseBladeBufferStart(false, 8 * kGiB, ceilings), BladeBufferStart::Half);
  EXPECT_EQ(chooseBladeBufferStart(false, 0, ceilings), BladeBufferStart::Half);  // no device-local heap reported
  EXPECT_EQ(chooseBladeBufferStart(true, 141 * kGiB, ceilings), BladeBufferStart::Small);  // lavapipe: host memory
}

TEST_F(BladePathTest, PlantsPastTheCeilingAreDroppedWholeAndCounted) {
  // A ceiling far under the field's needs: the expansion writes what fits, drops the rest whole
  // (counted), and draws nothing stray — no validation message, no pixel changed away from the
  // plants the uncapped renderer draws.
  RendererOptions o = options(kW, kH, 4);
  o.bladeMaxVertices = 60000;
  auto capped = Renderer::create(o);
  ASSERT_TRUE(capped.ok());
  auto full = makeRenderer(kW, kH, 4);
  ASSERT_TRUE(full);
  for (Renderer* r : {capped->get(), full.get()}) ASSERT_TRUE(r->setImageryLayers(1).ok());
  const PlantDrawOptions draw = withPath({}, BladePath::Compute);
  const FieldResult c = renderField(**capped, "grass", PlantStyle::Plants, draw);
  const FieldResult f = renderField(*full, "grass", PlantStyle::Plants, draw);
  ASSERT_TRUE(c.with.vegetation && f.with.vegetation);
  const VegetationFigures &vc = *c.with.vegetation, &vf = *f.with.vegetation;
  EXPECT_EQ(vc.plants, vf.plants) << "classified alike";
  EXPECT_EQ(vf.bladesDropped, 0u);
  EXPECT_GT(vc.bladesDropped, 0u);
  EXPECT_LE(vc.bladeVertices, 60000u);
  EXPECT_GT(vc.bladeTriangles, 0u);
  EXPECT_LT(vc.bladeTriangles, vf.bladeTriangles);
  // Every triangle drawn (degenerate ones included) reached the clipper: the capped frame's
  // count is the drawn indices / 3, never more than the uncapped frame's.
  EXPECT_LE(c.with.gpu.statistics.clippingInvocations, f.with.gpu.statistics.clippingInvocations);
  // The capped frame's plants are a subset of the uncapped frame's: next to nothing clearly
  // visible where the uncapped frame has no plant pixel nearby. Not exactly nothing: where the
  // uncapped frame's front blade happens to match the ground's colour, the capped frame may have
  // dropped it and show the darker blade or shadow behind. A stray triangle from a bad index
  // would cover far more than 0.1 % of the frame.
  EXPECT_LE(double(strayPixels(*c.with.color, *f.with.color, *f.without.color)), 0.001 * kW * kH);
  EXPECT_GT(changedPixels(*c.with.color, *c.without.color, 0, kH, 4), 100u) << "what fits is drawn";
  savePng("capped_compute.png", *c.with.color);
}

TEST_F(BladePathTest, EachPathIsDeterministic) {
  auto r = makeRenderer(kW, kH, 4);
  ASSERT_TRUE(r);
  ASSERT_TRUE(r->setImageryLayers(1).ok());
  for (BladePath path : {BladePath::Tessellation, BladePath::Compute}) {
    SCOPED_TRACE(bladePathName(path));
    const PlantDrawOptions draw = withPath({}, path);
    const FieldResult a = renderField(*r, "grass", PlantStyle::Plants, draw);
    const FieldResult b = renderField(*r, "grass", PlantStyle::Plants, draw);
    ASSERT_TRUE(a.with.vegetation && b.with.vegetation);
    EXPECT_EQ(a.with.vegetation->plants, b.with.vegetation->plants);
    EXPECT_EQ(a.with.vegetation->bladeTriangles, b.with.vegetation->bladeTriangles);
    EXPECT_EQ(a.with.gpu.statistics.clippingInvocations, b.with.gpu.statistics.clippingInvocations);
    EXPECT_EQ(a.with.gpu.statistics.fragmentInvocations, b.with.gpu.statistics.fragmentInvocations);
    // Groups (and so triangles) arrive in atomic order: equal-depth ties may resolve either way.
    EXPECT_LT(differing(*a.with.color, *b.with.color, 24), size_t(0.002 * kW * kH));
  }
}

// Issue 18: segment counts morph. A seed triangle's eq. 4 count depends on its distance in units
// of lodDistanceM; frames whose unit grows by 0.2 % each (the camera 0.2 % nearer each time, all
// else equal), 16 of them, change the count of the triangles that cross a whole-number boundary. Per plant, the centre
// line of its blade strip (the midpoints of the vertex pairs the compute path wrote, no shadows)
// in both frames, matched by root: over the plants whose count changed, the Hausdorff distance
// between the two centre lines. With the fades, the finer blade that has just gained a segment is
// the coarser blade (its new segment has no length yet); with --plant-fades off it steps to the
// finer polyline, a chord sag away.
using CentreLines = std::map<std::array<long long, 3>, std::vector<glm::vec3>>;

CentreLines centreLines(Renderer& r, const PlantDrawOptions& draw) {
  EXPECT_TRUE(renderPlantsFrame(r, draw, {0.0, 0.0, 2.0}));
  auto vertices = r.readBladeVertices();
  EXPECT_TRUE(vertices.ok());
  std::map<uint32_t, std::vector<glm::vec3>> strips;  // per plant record, in the order written
  for (const auto& v : *vertices)
    if ((v.plant >> 29) == 0u) strips[v.plant & 0x1fffffffu].push_back(v.pos);  // blades, not shadows
  CentreLines lines;
  for (const auto& [plant, strip] : strips) {
    std::vector<glm::vec3> line;
    for (size_t i = 0; i + 1 < strip.size(); i += 2) line.push_back(0.5f * (strip[i] + strip[i + 1]));
    const glm::vec3 root = line.front();
    lines[{std::llround(root.x * 1e4), std::llround(root.y * 1e4), std::llround(root.z * 1e4)}] = line;
  }
  return lines;
}

double pointToPolyline(const glm::vec3& p, const std::vector<glm::vec3>& line) {
  double best = 1e30;
  for (size_t i = 0; i + 1 < line.size(); ++i) {
    const glm::vec3 ab = line[i + 1] - line[i];
    const float t = glm::dot(ab, ab) > 0.0f ? std::clamp(glm::dot(p - line[i], ab) / glm::dot(ab, ab), 0.0f, 1.0f) : 0.0f;
    best = std::min(best, static_cast<double>(glm::length(p - (line[i] + t * ab))));
  }
  return best;
}

double hausdorff(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b) {
  double h = 0.0;
  for (const glm::vec3& p : a) h = std::max(h, pointToPolyline(p, b));
  for (const glm::vec3& p : b) h = std::max(h, pointToPolyline(p, a));
  return h;
}

TEST_F(BladePathTest, SegmentCountsMorphInsteadOfStepping) {
  auto r = makeRenderer(kW, kH, 1);
  ASSERT_TRUE(r);
  ASSERT_TRUE(r->setImageryLayers(1).ok());
  double worst[2] = {0.0, 0.0};
  size_t changed[2] = {0, 0};
  for (int fades = 0; fades < 2; ++fades) {
    PlantDrawOptions d;
    d.path = BladePath::Compute;
    d.shadows = false;
    d.maxSegments = 8;
    d.fades = fades == 1;
    d.lodDistanceM = 4.0f;
    CentreLines a = centreLines(*r, d);
    ASSERT_GT(a.size(), 100u);
    for (int step = 1; step <= 16; ++step) {
      d.lodDistanceM = 4.0f * std::pow(1.002f, static_cast<float>(step));
      CentreLines b = centreLines(*r, d);
      for (const auto& [root, line] : a) {
        const auto other = b.find(root);
        if (other == b.end() || other->second.size() == line.size()) continue;
        ++changed[fades];
        worst[fades] = std::max(worst[fades], hausdorff(line, other->second));
      }
      a = std::move(b);
    }
  }
  std::printf("plants whose segment count changed: %zu (fades off), %zu (fades on); largest centre-line "
              "change: %.3f mm stepping, %.3f mm morphing\n",
              changed[0], changed[1], worst[0] * 1e3, worst[1] * 1e3);
  EXPECT_GT(changed[0], 20u);
  EXPECT_EQ(changed[0], changed[1]);  // the same plants change count either way
  EXPECT_GT(worst[0], 1e-3);          // stepping moves the blade by millimetres: the check sees it
  // The morph moves a blade in proportion to the step (its last segment grows by the step's change
  // of eq. 4's count, here about 0.5 % of the count), stepping by the whole chord sag.
  EXPECT_LT(worst[1], 0.05 * worst[0]);
}

// Issue 18: no popping along a moving flight, judged per plant in world space so that the
// camera's own motion does not count: the camera flies 1 cm a frame for 24 frames over the field,
// whose seed triangles ask for plants by their projected area (lodCount ∝ 1 / d², as eq. 1 does),
// so plants appear and vanish at the ends of their sequences and blades change segment count.
// Per plant (matched by its root in the world; only plants well inside the view in both frames:
// the frustum test adds and drops whole groups at its edges, off screen), a plant that appears or
// vanishes between two frames is at most 2 % of the median blade's length then (the 2 % rule), and
// a plant in both frames moves (centre-line Hausdorff distance) at most 3 % of it in a step — the
// plants at the ends of their sequences grow and shrink continuously as the camera comes nearer. With --plant-fades off, plants pop in and out whole and blades step their
// segments, or the check would prove nothing.
struct FlightPlants {
  std::map<std::array<long long, 3>, std::vector<glm::vec3>> lines;  // world centre lines by root (1 mm)
  std::map<std::array<long long, 3>, std::vector<glm::vec3>> edge;   // those near the view's edges
  // The same plant in another frame: its root within 2 mm (the GPU places roots camera-relative in
  // float, so a root a rounding boundary away must still match).
  const std::vector<glm::vec3>* find(const glm::vec3& root) const { return nearest(lines, root); }
  const std::vector<glm::vec3>* findEdge(const glm::vec3& root) const { return nearest(edge, root); }
  static const std::vector<glm::vec3>* nearest(const std::map<std::array<long long, 3>, std::vector<glm::vec3>>& lines,
                                               const glm::vec3& root) {
    const std::vector<glm::vec3>* best = nullptr;
    double bestD = 2e-3;
    const std::array<long long, 3> k{std::llround(root.x * 1e3), std::llround(root.y * 1e3), std::llround(root.z * 1e3)};
    for (long long dx = -2; dx <= 2; ++dx)
      for (long long dy = -2; dy <= 2; ++dy)
        for (long long dz = -2; dz <= 2; ++dz) {
          const auto it = lines.find({k[0] + dx, k[1] + dy, k[2] + dz});
          if (it == lines.end()) continue;
          const double d = glm::length(it->second.front() - root);
          if (d <= bestD) {
            bestD = d;
            best = &it->second;
          }
        }
    return best;
  }
};

FlightPlants flightFrame(Renderer& r, const PlantDrawOptions& draw, const glm::dvec3& camera) {
  EXPECT_TRUE(renderPlantsFrame(r, draw, camera, [](std::vector<SeedTriangleGpu>& seeds) {
    for (SeedTriangleGpu& t : seeds) {  // eq. 1's count: the projected area falls with 1 / d²
      const glm::vec3 centroid = (glm::vec3(t.v0) + glm::vec3(t.v1) + glm::vec3(t.v2)) / 3.0f;
      t.lodCount = 2000.0f / std::max(glm::dot(centroid, centroid), 1.0f);
    }
  }));
  auto vertices = r.readBladeVertices();
  EXPECT_TRUE(vertices.ok());
  std::map<uint32_t, std::vector<glm::vec3>> strips;
  for (const auto& v : *vertices)
    if ((v.plant >> 29) == 0u) strips[v.plant & 0x1fffffffu].push_back(glm::vec3(glm::dvec3(v.pos) + camera));
  FlightPlants f;
  // Well inside the view: the root within 80 % of the half-angles from the view axis.
  const glm::dvec3 fwd = kFieldForward;
  const glm::dvec3 right = glm::normalize(glm::cross(fwd, glm::dvec3(0.0, 0.0, 1.0)));
  const glm::dvec3 up = glm::cross(right, fwd);
  const double tanV = std::tan(0.5 * Camera{}.verticalFovDeg * 3.14159265358979 / 180.0);
  const double tanH = tanV * double(kW) / double(kH);
  const auto inside = [&](const glm::vec3& world) {
    const glm::dvec3 v = glm::dvec3(world) - camera;
    const double z = glm::dot(v, fwd);
    return z > 0.5 && std::abs(glm::dot(v, right)) < 0.8 * tanH * z && std::abs(glm::dot(v, up)) < 0.8 * tanV * z;
  };
  for (const auto& [plant, strip] : strips) {
    std::vector<glm::vec3> line;
    for (size_t i = 0; i + 1 < strip.size(); i += 2) line.push_back(0.5f * (strip[i] + strip[i + 1]));
    const glm::vec3 root = line.front();
    (inside(root) ? f.lines : f.edge)[{std::llround(root.x * 1e3), std::llround(root.y * 1e3), std::llround(root.z * 1e3)}] =
        line;
  }
  return f;
}

float lineLength(const std::vector<glm::vec3>& line) {
  float l = 0.0f;
  for (size_t i = 0; i + 1 < line.size(); ++i) l += glm::length(line[i + 1] - line[i]);
  return l;
}

TEST_F(BladePathTest, NoPlantPopsAlongAMovingFlight) {
  auto r = makeRenderer(kW, kH, 1);
  ASSERT_TRUE(r);
  ASSERT_TRUE(r->setImageryLayers(1).ok());
  struct Figures {
    size_t plants = 0, appeared = 0, popped = 0, jumped = 0;
    double worstAppear = 0.0, worstMove = 0.0;  // fractions of the median blade length
  } fig[2];
  for (int fades = 0; fades < 2; ++fades) {
    PlantDrawOptions d;
    d.path = BladePath::Compute;
    d.shadows = false;
    d.maxSegments = 8;
    d.fades = fades == 1;
    FlightPlants before = flightFrame(*r, d, {0.0, 0.0, 2.0});
    std::vector<float> lengths;
    for (const auto& [root, line] : before.lines) lengths.push_back(lineLength(line));
    ASSERT_GT(lengths.size(), 200u);
    std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
    const double median = lengths[lengths.size() / 2];
    Figures& f = fig[fades];
    for (int frame = 1; frame <= 24; ++frame) {
      FlightPlants now = flightFrame(*r, d, {0.0, 0.01 * frame, 2.0});
      f.plants += now.lines.size();
      auto appearOrVanish = [&](const FlightPlants& a, const FlightPlants& b) {  // in a, not in b
        for (const auto& [root, line] : a.lines) {
          if (b.find(line.front()) || b.findEdge(line.front())) continue;
          ++f.appeared;
          const double frac = lineLength(line) / median;
          f.worstAppear = std::max(f.worstAppear, frac);
          if (frac > 0.02) ++f.popped;
        }
      };
      appearOrVanish(now, before);
      appearOrVanish(before, now);
      for (const auto& [root, line] : now.lines) {
        const std::vector<glm::vec3>* old = before.find(line.front());
        if (!old) continue;
        const double move = hausdorff(line, *old) / median;
        f.worstMove = std::max(f.worstMove, move);
        if (move > 0.03) ++f.jumped;
      }
      before = std::move(now);
    }
  }
  for (int fades = 1; fades >= 0; --fades)
    std::printf("fades %s: %zu plant-frames, %zu appeared or vanished (largest %.3f of the median blade, %zu over "
                "0.02), largest move %.4f (%zu over 0.03)\n",
                fades ? "on " : "off", fig[fades].plants, fig[fades].appeared, fig[fades].worstAppear,
                fig[fades].popped, fig[fades].worstMove, fig[fades].jumped);
  EXPECT_GT(fig[1].appeared, 20u);  // the flight does make plants come and go
  EXPECT_EQ(fig[1].popped, 0u);
  EXPECT_EQ(fig[1].jumped, 0u);
  EXPECT_GT(fig[0].popped, 20u) << "without the fades the check must see pops";
  EXPECT_GT(fig[0].worstMove, 2.0 * fig[1].worstMove) << "without the morph blades step their segments";
}

TEST_F(BladePathTest, MeshIsRefusedNamingTheOptionAndTheDeviceAndAutoIsCompute) {
  RendererOptions o = options(64, 36, 1);
  o.bladePath = BladePath::Mesh;
  auto refused = Renderer::create(o);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().kind, ErrorKind::InvalidInput);
  EXPECT_NE(refused.error().message.find("--blade-path mesh"), std::string::npos) << refused.error().message;
  EXPECT_NE(refused.error().message.find("VK_EXT_mesh_shader"), std::string::npos) << refused.error().message;
  o.bladePath = BladePath::Tessellation;
  auto tess = Renderer::create(o);
  ASSERT_TRUE(tess.ok());
  EXPECT_EQ((*tess)->bladePath(), BladePath::Tessellation);
  EXPECT_NE(refused.error().message.find((*tess)->device().name), std::string::npos) << refused.error().message;
  o.bladePath = BladePath::Auto;
  auto autoPath = Renderer::create(o);
  ASSERT_TRUE(autoPath.ok());
  EXPECT_EQ((*autoPath)->bladePath(), BladePath::Compute);
  EXPECT_EQ(parseBladePath("compute"), BladePath::Compute);
  EXPECT_FALSE(parseBladePath("fancy").has_value());
}

}  // namespace
}  // namespace vegstream::render::testing
