// streaming/dataset_snapshot.h's imagery mosaic (issue 20: the ground the trees read) on a
// synthetic dataset: the same pixels as the height mosaic, each one the tile pixel under it; a
// missing imagery tile is transparent (and without NDVI), a missing NDVI tile "no NDVI", and a dataset without
// imagery is an error.

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <vector>

#include <gtest/gtest.h>

#include "datasets/tile_codec.h"
#include "geo/projection.h"
#include "streaming/dataset_snapshot.h"
#include "streaming/local_tile_source.h"
#include "streaming_fixture.h"

namespace vegstream::streaming::test {
namespace {

struct Located {
  geo::TileId tile;
  int px = 0, py = 0;
};

// The tile and tile pixel of mosaic pixel (col, row).
Located locate(const MercatorRaster& g, int col, int row) {
  const double half = geo::kWebMercatorHalfWorldM;
  const auto gcol = static_cast<int64_t>(std::llround((g.x0 + half) / g.pixelM - 0.5)) + col;
  const auto grow = static_cast<int64_t>(std::llround((half - g.y0) / g.pixelM - 0.5)) + row;
  const int n = datasets::kTileSize;
  return {{g.zoom, static_cast<int>(gcol / n), static_cast<int>(grow / n)}, static_cast<int>(gcol % n),
          static_cast<int>(grow % n)};
}

TEST(GroundImagery, MosaicsTheImageryAndNdviOnTheHeightsPixels) {
  const fs::path dir = testTmp("ground_imagery");
  auto meta = makeSynthetic(dir);
  ASSERT_TRUE(meta.ok()) << meta.error().message;
  ASSERT_TRUE(meta->imagery.has_value());
  SnapshotLimits limits;
  limits.maxHeightPixels = 300'000;
  LocalTileSource source(dir);
  auto heights = loadGroundHeights(source, *meta, limits);
  ASSERT_TRUE(heights.ok()) << heights.error().message;

  // An NDVI layer written over the mosaic's tiles (byte 100 + tile x % 100), one tile left
  // without; and one imagery tile taken away.
  std::vector<geo::TileId> tiles;
  for (const geo::TileId& id : geo::tilesCovering(meta->bounds, heights->zoom)) tiles.push_back(id);
  ASSERT_GE(tiles.size(), 4u);
  for (size_t i = 1; i < tiles.size(); ++i) {
    datasets::ColorTile t;
    t.id = tiles[i];
    t.ndvi.assign(size_t(datasets::kTileSize) * datasets::kTileSize, static_cast<uint8_t>(100 + tiles[i].x % 100));
    ASSERT_TRUE(datasets::writeNdviTile(datasets::ndviTilePath(dir, tiles[i]), t).ok());
  }
  const geo::TileId gone = tiles[tiles.size() / 2];
  ASSERT_TRUE(fs::remove(dir / datasetRelativePath({TileLayer::Imagery, gone}, *meta)));
  datasets::DatasetMeta withNdvi = *meta;
  withNdvi.ndvi = true;

  auto imagery = loadGroundImagery(source, withNdvi, *heights);
  ASSERT_TRUE(imagery.ok()) << imagery.error().message;
  EXPECT_EQ(imagery->zoom, heights->zoom);
  ASSERT_EQ(imagery->width, heights->width);
  ASSERT_EQ(imagery->height, heights->height);
  EXPECT_EQ(imagery->x0, heights->x0);
  EXPECT_EQ(imagery->y0, heights->y0);
  ASSERT_EQ(imagery->rgba.size(), heights->heights.size() * 4);
  ASSERT_EQ(imagery->ndvi.size(), heights->heights.size());

  // Every 7th pixel against its tile: the same four bytes, NDVI as written (0 on the first tile),
  // transparent where the imagery tile is gone.
  size_t checked = 0, transparent = 0, noNdvi = 0;
  std::map<geo::TileId, std::vector<uint8_t>> decoded;
  for (int row = 0; row < imagery->height; row += 7)
    for (int col = 0; col < imagery->width; col += 7) {
      const Located at = locate(*imagery, col, row);
      const size_t i = size_t(row) * size_t(imagery->width) + size_t(col);
      const uint8_t* got = &imagery->rgba[4 * i];
      const size_t p = 4 * (size_t(at.py) * datasets::kTileSize + size_t(at.px));
      if (at.tile == gone) {
        ASSERT_EQ(got[3], 0) << col << ", " << row;
        ++transparent;
      } else {
        auto cached = decoded.find(at.tile);
        if (cached == decoded.end()) {
          auto tile = datasets::readColorTile(dir / datasetRelativePath({TileLayer::Imagery, at.tile}, *meta), at.tile,
                                              datasets::kTileSize);
          ASSERT_TRUE(tile.ok()) << tile.error().message;
          cached = decoded.emplace(at.tile, std::move(tile->rgba)).first;
        }
        for (int c = 0; c < 4; ++c) ASSERT_EQ(got[c], cached->second[p + size_t(c)]) << col << ", " << row;
      }
      // No NDVI without its imagery tile either (the mosaic reads them as a pair, as the streamer does).
      const uint8_t wantNdvi = at.tile == tiles[0] || at.tile == gone ? 0 : static_cast<uint8_t>(100 + at.tile.x % 100);
      ASSERT_EQ(imagery->ndvi[i], wantNdvi) << col << ", " << row;
      noNdvi += imagery->ndvi[i] == 0 ? 1 : 0;
      ++checked;
    }
  std::printf("[ figures  ] zoom %d, %d x %d pixels: %zu checked, %zu transparent, %zu without NDVI\n",
              imagery->zoom, imagery->width, imagery->height, checked, transparent, noNdvi);
  EXPECT_GT(checked, 1000u);
  EXPECT_GT(transparent, 0u);
  EXPECT_GT(noNdvi, 0u);

  // Without an NDVI layer the NDVI is empty; without imagery, an error naming the dataset.
  auto plain = loadGroundImagery(source, *meta, *heights);
  ASSERT_TRUE(plain.ok()) << plain.error().message;
  EXPECT_TRUE(plain->ndvi.empty());
  datasets::DatasetMeta noImagery = *meta;
  noImagery.imagery.reset();
  auto refused = loadGroundImagery(source, noImagery, *heights);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().kind, ErrorKind::InvalidInput);
  EXPECT_NE(refused.error().message.find("no imagery"), std::string::npos) << refused.error().message;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace vegstream::streaming::test
