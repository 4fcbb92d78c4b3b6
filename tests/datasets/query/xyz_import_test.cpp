// importXyzTiles on the grandcanyon-xyz sample: decoded heights, the two encodings of one tile,
// the lower zooms, paletted imagery, template matching, and a corrupt tile.

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "datasets/tile_codec.h"
#include "tests/datasets/query/query_fixture.h"

namespace vegstream::testing {
namespace {
namespace fs = std::filesystem;
using datasets::ElevationEncoding;

TEST_F(GrandCanyon, DecodedHeightsWithinKnownRange) {
  // The sample's README: decoded heights 439 … 2184 m.
  double lo = 1e9, hi = -1e9;
  for (int x : {758, 759})
    for (int y : {1608, 1609}) {
      const geo::TileId id{12, x, y};
      auto t = datasets::readHeightTile(
          grandCanyonDir() / "terrain-rgb/12" / std::to_string(x) / (std::to_string(y) + ".png"), id,
          ElevationEncoding::TerrainRgb, datasets::kTileSize);
      ASSERT_TRUE(t.ok()) << t.error().message;
      for (float h : t->heights) {
        ASSERT_FALSE(std::isnan(h));
        lo = std::min(lo, double{h});
        hi = std::max(hi, double{h});
      }
    }
  EXPECT_NEAR(lo, 439.0, 0.5);
  EXPECT_NEAR(hi, 2184.0, 0.5);
  EXPECT_NEAR(meta().minHeightM, lo, 1e-3);
  EXPECT_NEAR(meta().maxHeightM, hi, 1e-3);
}

// The sample's two files of 12/759/1608 are NOT the same raster in two encodings: they come
// from different DEMs (Mapbox vs. the Terrarium/SRTM mosaic), so pixels differ by up to ~76 m
// (median 3.1 m). What holds, and is asserted: both decode to the same terrain (correlation
// 0.9997, tile means 0.49 m apart), and each encoding carries the other's heights within 0.2 m.
TEST_F(GrandCanyon, TerrariumAndTerrainRgbAgree) {
  const geo::TileId id{12, 759, 1608};
  auto rgb = datasets::readHeightTile(grandCanyonDir() / "terrain-rgb/12/759/1608.png", id,
                                      ElevationEncoding::TerrainRgb, datasets::kTileSize);
  auto ter = datasets::readHeightTile(grandCanyonDir() / "terrarium/12/759/1608.png", id, ElevationEncoding::Terrarium,
                                      datasets::kTileSize);
  ASSERT_TRUE(rgb.ok()) << rgb.error().message;
  ASSERT_TRUE(ter.ok()) << ter.error().message;
  ASSERT_EQ(rgb->heights.size(), ter->heights.size());
  const double n = static_cast<double>(rgb->heights.size());
  double meanA = 0.0, meanB = 0.0;
  for (size_t i = 0; i < rgb->heights.size(); ++i) meanA += rgb->heights[i] / n, meanB += ter->heights[i] / n;
  double sab = 0.0, saa = 0.0, sbb = 0.0, maxRoundTrip = 0.0;
  std::vector<double> absDiff;
  for (size_t i = 0; i < rgb->heights.size(); ++i) {
    const double a = rgb->heights[i], b = ter->heights[i];
    sab += (a - meanA) * (b - meanB);
    saa += (a - meanA) * (a - meanA);
    sbb += (b - meanB) * (b - meanB);
    absDiff.push_back(std::abs(a - b));
    // Each encoding carries the other's heights: encode in the other, decode, compare.
    const auto ca = datasets::encodeHeight(a, ElevationEncoding::Terrarium);
    const auto cb = datasets::encodeHeight(b, ElevationEncoding::TerrainRgb);
    maxRoundTrip =
        std::max({maxRoundTrip, std::abs(datasets::decodeHeight(ca[0], ca[1], ca[2], ElevationEncoding::Terrarium) - a),
                  std::abs(datasets::decodeHeight(cb[0], cb[1], cb[2], ElevationEncoding::TerrainRgb) - b)});
  }
  std::nth_element(absDiff.begin(), absDiff.begin() + static_cast<std::ptrdiff_t>(absDiff.size() / 2), absDiff.end());
  const double correlation = sab / std::sqrt(saa * sbb);
  EXPECT_LE(maxRoundTrip, 0.2);
  EXPECT_NEAR(meanA, meanB, 1.0);
  EXPECT_GT(correlation, 0.999);
  EXPECT_LT(absDiff[absDiff.size() / 2], 5.0);
  RecordProperty("mean_diff_m", std::to_string(meanA - meanB));
  RecordProperty("median_abs_diff_m", std::to_string(absDiff[absDiff.size() / 2]));
}

TEST_F(GrandCanyon, ImportedTilesEqualTheSourceTiles) {
  for (int x : {758, 759})
    for (int y : {1608, 1609}) {
      const geo::TileId id{12, x, y};
      const fs::path rel = fs::path("12") / std::to_string(x) / (std::to_string(y) + ".png");
      auto src = datasets::readHeightTile(grandCanyonDir() / "terrain-rgb" / rel, id, ElevationEncoding::TerrainRgb,
                                          datasets::kTileSize);
      auto dst = datasets::readHeightTile(datasets::elevationTilePath(dir(), id), id, meta().elevationEncoding,
                                          datasets::kTileSize);
      ASSERT_TRUE(src.ok() && dst.ok());
      EXPECT_EQ(src->heights, dst->heights) << geo::toString(id);
    }
}

TEST_F(GrandCanyon, LowerZoomsAreMeansOfTheirChildren) {
  EXPECT_EQ(meta().maxZoom, 12);
  EXPECT_EQ(meta().minZoom, 11);  // the 2×2 tiles of zoom 12 share the parent 11/379/804
  EXPECT_EQ(meta().elevationTiles, 5u);
  EXPECT_EQ(meta().imageryTiles, 5u);
  const geo::TileId top{11, 379, 804};
  auto parent = datasets::readHeightTile(datasets::elevationTilePath(dir(), top), top, meta().elevationEncoding,
                                         datasets::kTileSize);
  ASSERT_TRUE(parent.ok()) << parent.error().message;
  double maxDiff = 0.0, parentSum = 0.0, childSum = 0.0;
  for (const geo::TileId& c : geo::children(top)) {
    auto child = datasets::readHeightTile(datasets::elevationTilePath(dir(), c), c, meta().elevationEncoding,
                                          datasets::kTileSize);
    ASSERT_TRUE(child.ok()) << child.error().message;
    const int ox = (c.x - 2 * top.x) * 128, oy = (c.y - 2 * top.y) * 128;
    for (int j = 0; j < 128; ++j)
      for (int i = 0; i < 128; ++i) {
        const double mean = (double{child->at(2 * i, 2 * j)} + child->at(2 * i + 1, 2 * j) +
                             child->at(2 * i, 2 * j + 1) + child->at(2 * i + 1, 2 * j + 1)) /
                            4.0;
        const double p = parent->at(ox + i, oy + j);
        maxDiff = std::max(maxDiff, std::abs(p - mean));
        parentSum += p;
        childSum += mean;
      }
  }
  // Each parent pixel is the mean of its 2×2 children, rounded to the 0.1 m step.
  EXPECT_LE(maxDiff, 0.05 + 1e-3);
  EXPECT_NEAR(parentSum / (256.0 * 256.0), childSum / (256.0 * 256.0), 0.01);
}

TEST_F(GrandCanyon, PalettedImageryDecodesToRgb) {
  const geo::TileId id{12, 759, 1609};
  auto src = datasets::readColorTile(grandCanyonDir() / "map/12/759/1609.png", id, datasets::kTileSize);
  ASSERT_TRUE(src.ok()) << src.error().message;
  std::set<uint32_t> colours;
  size_t nonGrey = 0;
  for (size_t i = 0; i < src->rgba.size(); i += 4) {
    colours.insert(uint32_t{src->rgba[i]} << 16 | uint32_t{src->rgba[i + 1]} << 8 | src->rgba[i + 2]);
    nonGrey += src->rgba[i] != src->rgba[i + 1] || src->rgba[i + 1] != src->rgba[i + 2];
  }
  EXPECT_GT(colours.size(), 8u);  // a palette expanded to many colours, not palette indices
  EXPECT_GT(nonGrey, 0u);
  ASSERT_TRUE(meta().imagery.has_value());
  auto dst = datasets::readColorTile(datasets::imageryTilePath(dir(), id, *meta().imagery), id, datasets::kTileSize);
  ASSERT_TRUE(dst.ok()) << dst.error().message;
  EXPECT_EQ(src->rgba, dst->rgba);
}

TEST(XyzTemplates, FindsTilesAndRejectsBadTemplates) {
  auto files = datasets::findXyzTiles((grandCanyonDir() / "terrain-rgb/{z}/{x}/{y}.png").string());
  ASSERT_TRUE(files.ok()) << files.error().message;
  ASSERT_EQ(files->size(), 4u);
  EXPECT_EQ(files->front().id, (geo::TileId{12, 758, 1608}));
  auto noY = datasets::findXyzTiles((grandCanyonDir() / "terrain-rgb/{z}/{x}/tile.png").string());
  ASSERT_FALSE(noY.ok());
  EXPECT_EQ(noY.error().kind, ErrorKind::InvalidInput);
  EXPECT_NE(noY.error().message.find("{y}"), std::string::npos);
  auto missing = datasets::findXyzTiles((grandCanyonDir() / "nothing-here/{z}/{x}/{y}.png").string());
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.error().kind, ErrorKind::NotFound);
}

TEST(XyzImport, CorruptTileIsRefusedAndLeavesNothing) {
  const fs::path work = testTmp("corrupt");
  fs::create_directories(work);
  fs::copy(grandCanyonDir() / "terrain-rgb", work / "src", fs::copy_options::recursive);
  const fs::path bad = work / "src/12/759/1609.png";
  {
    std::ofstream f(bad, std::ios::binary | std::ios::trunc);
    f << "this is not a PNG file, just garbage bytes \x01\x02\x03";
  }
  datasets::XyzImportOptions o;
  o.elevationTemplate = (work / "src/{z}/{x}/{y}.png").string();
  o.encoding = ElevationEncoding::TerrainRgb;
  o.out = work / "out";
  auto r = datasets::importXyzTiles(o, makeNullLogger());
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().kind, ErrorKind::InvalidInput);
  EXPECT_NE(r.error().message.find("1609.png"), std::string::npos) << r.error().message;
  EXPECT_FALSE(fs::exists(o.out));
  size_t left = 0;  // no temporary directory beside --out either
  for (const auto& e : fs::directory_iterator(work)) left += e.path().filename() != "src";
  EXPECT_EQ(left, 0u);

  // The same through the command line, when the import subcommand is there.
  const auto help = runVegstream("import --help");
  if (help.exitCode == 0 && help.out.find("--xyz-elevation") != std::string::npos) {
    const auto cmd = runVegstream("import --xyz-elevation '" + o.elevationTemplate +
                                  "' --encoding terrain-rgb --out '" + o.out.string() + "'");
    EXPECT_EQ(cmd.exitCode, 2);
    EXPECT_NE(cmd.err.find("1609.png"), std::string::npos) << cmd.err;
    EXPECT_FALSE(fs::exists(o.out));
  }
  fs::remove_all(work);
}

}  // namespace
}  // namespace vegstream::testing
