// The classify pass inside the renderer: seed triangles on a flat field coloured by one
// imagery layer go through classification and the marker draws (render/plant_marker_pass.h).
// A green field grows grass markers near the camera (and nothing in the sky); a red-rock field
// grows gravel and no grass; a pale-sandstone field grows nothing; a forest-coloured field is
// classified as trees, drawn as markers in the markers style and not at all in the plants style
// (trees have no model yet). Validation stays silent.

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "core/hash.h"
#include "plant_field.h"
#include "vegetation/colour_score.h"
#include "vegetation/species_catalog.h"

namespace vegstream::render::testing {
namespace {

class PlantMarkers : public GpuTest {};

TEST_F(PlantMarkers, AGreenFieldGrowsGrassNearTheCameraAndNothingInTheSky) {
  auto r = makeRenderer(kW, kH, 4);
  ASSERT_TRUE(r);
  ASSERT_TRUE(r->setImageryLayers(1).ok());
  const FieldResult f = renderField(*r, "grass", PlantStyle::Markers);  // the grass reference colour
  ASSERT_TRUE(f.with.vegetation.has_value());
  const VegetationFigures& v = *f.with.vegetation;
  EXPECT_TRUE(v.gpuCounts);
  EXPECT_EQ(v.seedTriangles, 2u * 20u * 19u);
  const int grass = speciesIndex("grass");
  ASSERT_GE(grass, 0);
  EXPECT_GT(v.plants[size_t(grass)], 0.9 * static_cast<double>(v.plantsTotal));
  EXPECT_GT(v.plantsTotal, 10000u);
  EXPECT_FALSE(v.overflow);
  // The classify and plants passes were timed; the markers changed the ground, not the sky.
  bool classify = false, plants = false;
  for (const PassTime& p : f.with.gpu.passes) {
    classify = classify || p.pass == "classify";
    plants = plants || p.pass == "plants";
  }
  EXPECT_TRUE(classify && plants);
  // The horizon is 18 % down the image; the seeded ground reaches from there to half-way.
  const size_t ground = changedPixels(*f.with.color, *f.without.color, kH / 5, kH / 2);
  const size_t sky = changedPixels(*f.with.color, *f.without.color, 0, kH / 10);
  EXPECT_GT(ground, size_t{kW} * (kH / 2 - kH / 5) / 4) << "markers cover a quarter of the seeded ground";
  EXPECT_EQ(sky, 0u);
}

TEST_F(PlantMarkers, ARedRockFieldGrowsGravelAndAPaleOneNothing) {
  auto r = makeRenderer(kW, kH, 1);
  ASSERT_TRUE(r);
  ASSERT_TRUE(r->setImageryLayers(1).ok());
  const FieldResult red = renderField(*r, "red gravel", PlantStyle::Markers);
  ASSERT_TRUE(red.with.vegetation.has_value());
  const int gravel = speciesIndex("red gravel"), grass = speciesIndex("grass");
  ASSERT_GE(gravel, 0);
  EXPECT_GT(red.with.vegetation->plants[size_t(gravel)], 0.9 * static_cast<double>(red.with.vegetation->plantsTotal));
  EXPECT_EQ(red.with.vegetation->plants[size_t(grass)], 0u);
  EXPECT_GT(changedPixels(*red.with.color, *red.without.color, kH / 2, kH), 100u);

  const FieldResult pale = renderField(*r, "pale sandstone", PlantStyle::Markers);
  ASSERT_TRUE(pale.with.vegetation.has_value());
  EXPECT_EQ(pale.with.vegetation->plantsTotal, 0u);
  EXPECT_GT(pale.with.vegetation->clusters, 0u);  // seeded, then rejected as bare soil
  EXPECT_EQ(changedPixels(*pale.with.color, *pale.without.color, 0, kH), 0u);
}

// Trees grow on their own grid (issue 20, vegetation/tree_placement.h, render/tree_pass.h): to the
// plants' classify pass a tree species is bare soil — its seeds are made and rejected, no group,
// no marker, nothing drawn as plants.
TEST_F(PlantMarkers, TreeSpeciesAreBareSoilToThePlants) {
  auto r = makeRenderer(kW, kH, 4);
  ASSERT_TRUE(r);
  ASSERT_TRUE(r->setImageryLayers(1).ok());
  const int conifer = speciesIndex("conifer");
  ASSERT_GE(conifer, 0);
  const FieldResult markers = renderField(*r, "conifer", PlantStyle::Markers);
  const FieldResult plants = renderField(*r, "conifer", PlantStyle::Plants);
  ASSERT_TRUE(markers.with.vegetation && plants.with.vegetation);
  EXPECT_GT(markers.with.vegetation->clusters, 1000u);  // seeded …
  EXPECT_EQ(markers.with.vegetation->plants[size_t(conifer)], 0u);  // … and rejected
  EXPECT_LT(double(markers.with.vegetation->plantsTotal), 0.1 * double(markers.with.vegetation->clusters));
  EXPECT_EQ(plants.with.vegetation->plants[size_t(conifer)], 0u);
  // The few plants of other species that the conifer's colour leaves (grass at its border) only.
  EXPECT_LT(changedPixels(*plants.with.color, *plants.without.color, 0, kH), kW * kH / 100) << "no tree drawn as plants";
}

}  // namespace
}  // namespace vegstream::render::testing
