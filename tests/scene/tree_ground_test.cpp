// scene/tree_ground.h (issue 20) on the Zion sample with NDVI: a point in the Kolob plateau's
// forest reads as dark green with a living NDVI on the ground's height; outside the data, or with
// the imagery gone, nothing is valid; the callback is the same function as sample().

#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "scene/tree_ground.h"
#include "streaming/local_tile_source.h"
#include "streaming/open_tile_source.h"
#include "tests/scene/zion_trees_fixture.h"

namespace vegstream::scene {
namespace {


TEST(TreeGround, KolobForestIsDarkGreenWithLivingNdviOnTheGround) {
  const auto dir = testing::zionWithNdvi();
  ASSERT_TRUE(dir.ok()) << dir.error().message;
  streaming::LocalTileSource source(*dir);
  auto meta = streaming::readMetaFrom(source);
  ASSERT_TRUE(meta.ok()) << meta.error().message;
  ASSERT_TRUE(meta->ndvi);
  const geo::GeoBounds& b = meta->bounds;
  const geo::LocalFrame frame({0.5 * (b.southDeg + b.northDeg), b.centre().x, 0.0});  // the scene's
  auto ground = TreeGround::load(source, *meta, frame, TreeGround::defaultLimits());
  ASSERT_TRUE(ground.ok()) << ground.error().message;
  EXPECT_EQ(ground->zoom(), 12) << "Zion's finest zoom within 4 Mpixels";

  // The plateau forest west of Kolob Reservoir (Landsat: about #121a0e, NDVI 0.39).
  const geo::Geodetic kolob{37.455, -113.075, 2400.0};
  const glm::dvec3 at = frame.toLocal(kolob);
  const vegetation::TreeGroundSample s = ground->sample(at.x, at.y);
  std::printf("[ figures  ] Kolob forest: linear (%.4f, %.4f, %.4f), NDVI %.3f, z %.1f m (zoom %d, %.1f MB)\n",
              s.linearRgb.r, s.linearRgb.g, s.linearRgb.b, s.ndvi, s.heightM, ground->zoom(), double(ground->bytes()) / 1e6);
  ASSERT_TRUE(s.valid);
  EXPECT_GT(s.linearRgb.g, s.linearRgb.r);
  EXPECT_GT(s.linearRgb.g, s.linearRgb.b);
  EXPECT_LT(s.linearRgb.g, 0.05f) << "dark";
  EXPECT_GT(s.ndvi, 0.2f);
  // On the ground: the point's lat/lon at z is where the DEM says it is, within the plateau's heights.
  const geo::Geodetic back = frame.toGeodetic({at.x, at.y, s.heightM});
  EXPECT_GT(back.heightM, 2000.0);
  EXPECT_LT(back.heightM, 2700.0);
  EXPECT_NEAR(back.latDeg, kolob.latDeg, 2e-4);  // within ~20 m: the tilt of up at z = 0 vs the ground
  EXPECT_NEAR(back.lonDeg, kolob.lonDeg, 2e-4);
  // The callback gives the same sample.
  const vegetation::TreeGroundSample c = ground->at()(at.x, at.y);
  EXPECT_EQ(c.valid, s.valid);
  EXPECT_EQ(c.linearRgb, s.linearRgb);
  EXPECT_EQ(c.ndvi, s.ndvi);
  EXPECT_EQ(c.heightM, s.heightM);

  // Outside the dataset: 30 km east of its centre (it spans 34 km), and far north.
  EXPECT_FALSE(ground->sample(30000.0, 0.0).valid);
  EXPECT_FALSE(ground->sample(0.0, 80000.0).valid);
  // Without its imagery (an empty mosaic of the same grid), nothing is valid.
  auto heights = streaming::loadGroundHeights(source, *meta, TreeGround::defaultLimits());
  ASSERT_TRUE(heights.ok());
  streaming::ImageryMosaic none;
  static_cast<streaming::MercatorRaster&>(none) = *heights;
  none.rgba.assign(heights->heights.size() * 4, 0);
  const TreeGround bare(*heights, none, frame);
  EXPECT_FALSE(bare.sample(at.x, at.y).valid);
}

}  // namespace
}  // namespace vegstream::scene
