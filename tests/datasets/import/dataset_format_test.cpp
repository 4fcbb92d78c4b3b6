// dataset.json: a full round trip, and bad fields refused with the file and the field named.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "datasets/dataset_format.h"
#include "tests/support/test_dirs.h"

namespace vegstream::datasets {
namespace {
namespace fs = std::filesystem;

fs::path freshDir(const std::string& name) {
  const fs::path d = vegstream::testing::testOutputDir() / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

DatasetMeta sample() {
  DatasetMeta m;
  m.name = "zion";
  m.bounds = {-113.2396, 37.1321, -112.8521, 37.5129};
  m.minZoom = 9;
  m.maxZoom = 13;
  m.minHeightM = 1024.25;
  m.maxHeightM = 2892.0;
  m.elevationEncoding = ElevationEncoding::TerrainRgb;
  m.imagery = ImageryFormat::Jpeg;
  m.attribution = "SRTM (CGIAR-CSI), Landsat 8 (USGS)";
  m.sources = {{"elevation", "srtm.tif", "WGS 84 (EPSG:4326)", "465x457"},
               {"imagery", "landsat_b4.tif", "WGS 84 / UTM zone 12N (EPSG:32612)", "1128x1428"}};
  m.elevationTiles = 123;
  m.imageryTiles = 120;
  m.bytes = 9876543210ull;
  return m;
}

void expectSame(const DatasetMeta& a, const DatasetMeta& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.bounds, b.bounds);
  EXPECT_EQ(a.minZoom, b.minZoom);
  EXPECT_EQ(a.maxZoom, b.maxZoom);
  EXPECT_EQ(a.minHeightM, b.minHeightM);
  EXPECT_EQ(a.maxHeightM, b.maxHeightM);
  EXPECT_EQ(a.elevationEncoding, b.elevationEncoding);
  EXPECT_EQ(a.imagery, b.imagery);
  EXPECT_EQ(a.tileSize, b.tileSize);
  EXPECT_EQ(a.attribution, b.attribution);
  ASSERT_EQ(a.sources.size(), b.sources.size());
  for (size_t i = 0; i < a.sources.size(); ++i) {
    EXPECT_EQ(a.sources[i].role, b.sources[i].role);
    EXPECT_EQ(a.sources[i].path, b.sources[i].path);
    EXPECT_EQ(a.sources[i].crs, b.sources[i].crs);
    EXPECT_EQ(a.sources[i].description, b.sources[i].description);
  }
  EXPECT_EQ(a.elevationTiles, b.elevationTiles);
  EXPECT_EQ(a.imageryTiles, b.imageryTiles);
  EXPECT_EQ(a.bytes, b.bytes);
}

TEST(DatasetFormat, RoundTripKeepsEveryField) {
  const fs::path d = freshDir("round");
  const DatasetMeta m = sample();
  ASSERT_TRUE(writeDatasetMeta(d, m));
  auto back = readDatasetMeta(d);
  ASSERT_TRUE(back) << back.error().message;
  expectSame(m, *back);

  DatasetMeta noImagery = sample();
  noImagery.imagery.reset();
  noImagery.imageryTiles = 0;
  ASSERT_TRUE(writeDatasetMeta(d, noImagery));
  auto back2 = readDatasetMeta(d);
  ASSERT_TRUE(back2) << back2.error().message;
  expectSame(noImagery, *back2);
}

TEST(DatasetFormat, TilePathsFollowTheXyzScheme) {
  EXPECT_EQ(elevationTilePath("D", {12, 758, 1608}), fs::path("D/elevation/12/758/1608.png"));
  EXPECT_EQ(imageryTilePath("D", {12, 758, 1608}, ImageryFormat::Jpeg), fs::path("D/imagery/12/758/1608.jpg"));
  EXPECT_EQ(imageryTilePath("D", {3, 1, 2}, ImageryFormat::Png), fs::path("D/imagery/3/1/2.png"));
}

// Rewrites one field of a valid dataset.json and returns the error message of reading it back.
std::string errorAfterEdit(const std::string& from, const std::string& to) {
  const fs::path d = freshDir("edit");
  EXPECT_TRUE(writeDatasetMeta(d, sample()));
  std::stringstream ss;
  ss << std::ifstream(d / "dataset.json").rdbuf();
  std::string text = ss.str();
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at == std::string::npos) return {};
  text.replace(at, from.size(), to);
  std::ofstream(d / "dataset.json") << text;
  auto r = readDatasetMeta(d);
  EXPECT_FALSE(r);
  return r ? std::string() : r.error().message;
}

TEST(DatasetFormat, BadFieldsAreNamed) {
  std::string m = errorAfterEdit("\"max_zoom\": 13", "\"max_zoom\": \"thirteen\"");
  EXPECT_NE(m.find("max_zoom"), std::string::npos) << m;
  EXPECT_NE(m.find("dataset.json"), std::string::npos) << m;
  m = errorAfterEdit("\"encoding\": \"terrain-rgb\"", "\"encoding\": \"lerc\"");
  EXPECT_NE(m.find("elevation.encoding"), std::string::npos) << m;
  m = errorAfterEdit("\"north\": 37.5129", "\"north\": 137.5");
  EXPECT_NE(m.find("bounds.north"), std::string::npos) << m;
  m = errorAfterEdit("\"min_zoom\": 9", "\"min_zoom\": 14");
  EXPECT_NE(m.find("min_zoom"), std::string::npos) << m;
  m = errorAfterEdit("\"bytes\": 9876543210", "\"bites\": 1");
  EXPECT_NE(m.find("'bytes' is missing"), std::string::npos) << m;
  m = errorAfterEdit("{", "[");
  EXPECT_NE(m.find("not valid JSON"), std::string::npos) << m;
}

TEST(DatasetFormat, NewerFormatVersionIsUnsupported) {
  const fs::path d = freshDir("version");
  DatasetMeta m = sample();
  m.formatVersion = 2;
  ASSERT_TRUE(writeDatasetMeta(d, m));
  auto r = readDatasetMeta(d);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().kind, ErrorKind::Unsupported);
  EXPECT_NE(r.error().message.find("format_version"), std::string::npos);
}

TEST(DatasetFormat, MissingDatasetIsNotFound) {
  auto r = readDatasetMeta(freshDir("empty"));
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().kind, ErrorKind::NotFound);
  EXPECT_NE(r.error().message.find("dataset.json"), std::string::npos);
}

}  // namespace
}  // namespace vegstream::datasets
