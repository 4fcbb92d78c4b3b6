// The landcover layer end to end through the API the importer calls (datasets/README.md,
// "Landcover layer"), on a hand-made geographic class raster: check it, histogram → scheme and
// the unknown-code warning, sample every max-zoom tile pixel centre with nearestClass, write the
// tiles, finishDataset (pyramid + dataset.json), then read back: the reader gives the source's
// class at the max zoom, and every lower-zoom pixel is a class of the source (the mode), the
// block's own class inside a block.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iterator>
#include <set>

#include "datasets/dataset_finish.h"
#include "datasets/dataset_reader.h"
#include "datasets/landcover.h"
#include "tests/support/test_dirs.h"

namespace vegstream::datasets {
namespace {
namespace fs = std::filesystem;

constexpr double kWest = 7.9, kNorth = 46.6, kStep = 0.0005;  // degrees; 60 × 40 pixels
constexpr int kWidth = 60, kHeight = 40, kBlock = 10, kMaxZoom = 14, kMinZoom = 12;
constexpr uint8_t kCodes[] = {10, 20, 30, 40, 50, 60, 80, 95};

// Blocks of 10 × 10 pixels cycling through kCodes; block (2, 1) holds the unknown code 7,
// block (5, 3) is nodata (255).
uint8_t sourceClass(int col, int row) {
  const int bx = col / kBlock, by = row / kBlock;
  if (bx == 2 && by == 1) return 7;
  if (bx == 5 && by == 3) return 255;
  return kCodes[static_cast<size_t>(by * 6 + bx) % std::size(kCodes)];
}

Raster classRaster() {
  Raster r;
  r.path = "worldcover_patch.tif";
  r.width = kWidth;
  r.height = kHeight;
  r.channels = 1;
  r.nodata = 255.0;
  r.georef.transform = {kWest, kStep, 0.0, kNorth, 0.0, -kStep};
  for (int row = 0; row < kHeight; ++row)
    for (int col = 0; col < kWidth; ++col) r.samples.push_back(sourceClass(col, row));
  return r;
}

// Continuous source pixel coordinates of a lon/lat (the inverse of the raster's affine map).
glm::dvec2 sourcePixel(glm::dvec2 lonLat) { return {(lonLat.x - kWest) / kStep, (kNorth - lonLat.y) / kStep}; }

// The importer's loop for one tile: every pixel centre → source pixel → nearest class.
LandcoverTile sampleTile(const Raster& r, const geo::TileId& id) {
  LandcoverTile t;
  t.id = id;
  t.classes.resize(size_t(kTileSize) * kTileSize);
  for (int j = 0; j < kTileSize; ++j)
    for (int i = 0; i < kTileSize; ++i) {
      const glm::dvec2 ll = geo::tileXYToLonLat({id.x + (i + 0.5) / kTileSize, id.y + (j + 0.5) / kTileSize}, id.z);
      t.classes[size_t(j) * kTileSize + size_t(i)] = nearestClass(r, sourcePixel(ll));
    }
  return t;
}

TEST(LandcoverImportFlow, SourceClassesSurviveTheTilesAndThePyramid) {
  const Raster r = classRaster();
  ASSERT_TRUE(checkClassRaster(r));
  const ClassHistogram h = classHistogram(r);
  auto scheme = detectLandcoverScheme(h, r.path);
  ASSERT_TRUE(scheme) << scheme.error().message;
  EXPECT_EQ(*scheme, LandcoverScheme::WorldCover);
  EXPECT_EQ(unknownClassesWarning(unknownClasses(h, *scheme), *scheme),
            "class 7: 100 pixels, unknown to worldcover; it grows nothing");

  const fs::path dir = vegstream::testing::testOutputDir() / "flow";
  DatasetMeta meta;
  meta.name = "flow";
  meta.bounds = {kWest, kNorth - kHeight * kStep, kWest + kWidth * kStep, kNorth};
  meta.minZoom = kMinZoom;
  meta.maxZoom = kMaxZoom;
  meta.landcover = *scheme;
  const glm::dvec2 nw = geo::lonLatToTileXY({meta.bounds.westDeg, meta.bounds.northDeg}, kMaxZoom);
  const glm::dvec2 se = geo::lonLatToTileXY({meta.bounds.eastDeg, meta.bounds.southDeg}, kMaxZoom);
  for (int y = int(nw.y); y <= int(se.y); ++y)
    for (int x = int(nw.x); x <= int(se.x); ++x) {
      const LandcoverTile t = sampleTile(r, {kMaxZoom, x, y});
      if (std::all_of(t.classes.begin(), t.classes.end(), [](uint8_t c) { return c == 0; })) continue;
      ASSERT_TRUE(writeLandcoverTile(landcoverTilePath(dir, t.id), t));
      ++meta.landcoverTiles;
      meta.bytes += fileBytes(landcoverTilePath(dir, t.id));
    }
  ASSERT_GE(meta.landcoverTiles, 2u);
  NullProgress progress;
  auto done = finishDataset(dir, meta, progress, 1, 90);
  ASSERT_TRUE(done) << done.error().message;

  uint64_t files = 0;
  std::set<int> lowerClasses;
  for (const auto& e : fs::recursive_directory_iterator(dir / "landcover")) {
    if (!e.is_regular_file()) continue;
    ++files;
    const int z = std::stoi(e.path().parent_path().parent_path().filename().string());
    if (z == kMaxZoom) continue;
    auto t = readLandcoverTile(e.path(), {});
    ASSERT_TRUE(t) << t.error().message;
    lowerClasses.insert(t->classes.begin(), t->classes.end());
  }
  EXPECT_EQ(files, done->landcoverTiles);
  // Classes of the source only (the mode, never a mean; nodata stays 0, 255 never appears).
  for (int c : lowerClasses) EXPECT_TRUE(c == 0 || c == 7 || std::count(kCodes, std::end(kCodes), c)) << c;
  EXPECT_TRUE(lowerClasses.count(95) && lowerClasses.count(7));

  auto reader = DatasetReader::open(dir);
  ASSERT_TRUE(reader) << reader.error().message;
  int compared = 0;
  for (int k = 0; k < 400; ++k) {  // source pixel centres and points between them
    const double col = std::fmod(k * 7.31, kWidth), row = std::fmod(k * 3.17, kHeight);
    const uint8_t expected = nearestClass(r, {col, row});
    const glm::dvec2 ll{kWest + col * kStep, kNorth - row * kStep};
    auto got = reader->landcoverAt(ll.y, ll.x);
    ASSERT_TRUE(got) << got.error().message;
    // Within half a max-zoom pixel of a source pixel edge the tile pixel's centre may fall in the
    // neighbour: compare away from the edges.
    const double fx = col - std::floor(col), fy = row - std::floor(row);
    if (expected == 0 || fx < 0.15 || fx > 0.85 || fy < 0.15 || fy > 0.85) continue;
    EXPECT_EQ(*got, std::optional<uint8_t>(expected)) << col << ", " << row;
    ++compared;
  }
  EXPECT_GT(compared, 150);
  // At zoom 12, the pixel at a block's centre is that block's class.
  for (int by = 0; by < kHeight / kBlock; ++by)
    for (int bx = 0; bx < kWidth / kBlock; ++bx) {
      const uint8_t c = sourceClass(bx * kBlock, by * kBlock);
      const glm::dvec2 ll{kWest + (bx + 0.5) * kBlock * kStep, kNorth - (by + 0.5) * kBlock * kStep};
      const glm::dvec2 t = geo::lonLatToTileXY(ll, kMinZoom);
      auto tile = reader->landcoverTile({kMinZoom, int(t.x), int(t.y)});
      ASSERT_TRUE(tile && *tile);
      const int i = int((t.x - std::floor(t.x)) * kTileSize), j = int((t.y - std::floor(t.y)) * kTileSize);
      EXPECT_EQ((*tile)->at(i, j), c == 255 ? 0 : c) << bx << ", " << by;
    }
}

}  // namespace
}  // namespace vegstream::datasets
