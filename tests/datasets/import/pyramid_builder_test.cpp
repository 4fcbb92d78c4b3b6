// The pyramid builder: a parent tile is the 2×2 mean of its children, nodata stays nodata, and
// every zoom down to minZoom is written and counted.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "datasets/pyramid_builder.h"
#include "datasets/tile_codec.h"
#include "tests/support/test_dirs.h"

namespace vegstream::datasets {
namespace {
namespace fs = std::filesystem;

TEST(PyramidBuilder, ParentIsTheMeanOfValidChildren) {
  const fs::path d = vegstream::testing::testOutputDir() / "pyramid";
  fs::remove_all(d);
  DatasetMeta meta;
  meta.minZoom = 8;
  meta.maxZoom = 10;
  meta.imagery = ImageryFormat::Png;
  // Two children of tile 9/100/200: NW (10/200/400) and SE (10/201/401).
  for (const geo::TileId id : {geo::TileId{10, 200, 400}, geo::TileId{10, 201, 401}}) {
    HeightTile h;
    h.id = id;
    h.heights.resize(256 * 256);
    ColorTile c;
    c.id = id;
    c.rgba.resize(256 * 256 * 4);
    for (int y = 0; y < 256; ++y)
      for (int x = 0; x < 256; ++x) {
        const size_t i = size_t(y) * 256 + size_t(x);
        // Column x has height 100 + x; pixel (1, 0) of every 2×2 block is nodata.
        h.heights[i] = (x % 2 == 1 && y % 2 == 0) ? NAN : float(100 + x);
        c.rgba[i * 4 + 0] = uint8_t(x);
        c.rgba[i * 4 + 1] = 50;
        c.rgba[i * 4 + 2] = 200;
        c.rgba[i * 4 + 3] = 255;
      }
    ASSERT_TRUE(writeHeightTile(elevationTilePath(d, id), h, meta.elevationEncoding));
    ASSERT_TRUE(writeColorTile(imageryTilePath(d, id, ImageryFormat::Png), c, ImageryFormat::Png));
  }
  NullProgress progress;
  ASSERT_TRUE(buildLowerZooms(d, meta, progress));
  EXPECT_EQ(meta.elevationTiles, 2u);  // 9/100/200 and 8/50/100
  EXPECT_EQ(meta.imageryTiles, 2u);
  EXPECT_GT(meta.bytes, 0u);

  auto p = readHeightTile(elevationTilePath(d, {9, 100, 200}), {9, 100, 200}, meta.elevationEncoding, kTileSize);
  ASSERT_TRUE(p) << p.error().message;
  // NW quadrant pixel (i, j) ← child pixels x = 2i, 2i+1 with (2i+1, 2j) missing: mean of
  // 100+2i, 100+2i, 100+2i+1 = 100 + 2i + 1/3.
  EXPECT_NEAR(p->at(10, 10), 100 + 20 + 1.0 / 3.0, 1.0 / 256.0);
  EXPECT_TRUE(std::isnan(p->at(200, 10)));  // NE child missing
  EXPECT_NEAR(p->at(130, 200), 100 + 2 * (130 - 128) + 1.0 / 3.0, 1.0 / 256.0);
  auto c = readColorTile(imageryTilePath(d, {9, 100, 200}, ImageryFormat::Png), {9, 100, 200}, kTileSize);
  ASSERT_TRUE(c);
  EXPECT_EQ(c->rgba[(size_t(10) * 256 + 10) * 4 + 0], 21);  // mean of 20, 21, 20, 21 rounded
  EXPECT_EQ(c->rgba[(size_t(10) * 256 + 200) * 4 + 3], 0);
  EXPECT_TRUE(fs::exists(elevationTilePath(d, {8, 50, 100})));
}

}  // namespace
}  // namespace vegstream::datasets
