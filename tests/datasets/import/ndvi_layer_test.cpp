// The NDVI layer's parts without an import: the byte encoding, the NDVI tile codec, the "ndvi"
// field of dataset.json (present, null, missing, malformed), the NDVI of one pixel, and the
// pyramid builder's mean of valid child values.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <nlohmann/json.hpp>

#include "datasets/dataset_format.h"
#include "datasets/ndvi_source.h"
#include "datasets/pyramid_builder.h"
#include "datasets/tile_codec.h"
#include "tests/support/test_dirs.h"

namespace vegstream::datasets {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;

fs::path freshDir(const std::string& name) {
  const fs::path d = vegstream::testing::testOutputDir() / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::vector<uint8_t> fileBytesOf(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(NdviEncoding, BytesAndBack) {
  EXPECT_EQ(ndviToByte(NAN), 0);
  EXPECT_TRUE(std::isnan(ndviFromByte(0)));
  EXPECT_EQ(ndviToByte(0.0f), 128);
  EXPECT_EQ(ndviToByte(1.0f), 255);
  EXPECT_EQ(ndviToByte(-1.0f), 1);
  EXPECT_EQ(ndviToByte(3.0f), 255);    // clamped
  EXPECT_EQ(ndviToByte(-3.0f), 1);     // clamped, never the "no data" byte
  EXPECT_EQ(ndviToByte(-INFINITY), 1);
  EXPECT_FLOAT_EQ(ndviFromByte(255), 1.0f);
  EXPECT_FLOAT_EQ(ndviFromByte(1), -1.0f);
  EXPECT_FLOAT_EQ(ndviFromByte(128), 0.0f);
  for (int i = 0; i <= 2000; ++i) {
    const float v = -1.0f + static_cast<float>(i) / 1000.0f;
    EXPECT_NEAR(ndviFromByte(ndviToByte(v)), v, 0.5f / 127.0f + 1e-6f) << v;
  }
  for (int b = 1; b <= 255; ++b) EXPECT_EQ(ndviToByte(ndviFromByte(static_cast<uint8_t>(b))), b);
}

TEST(NdviEncoding, NdviOfOnePixel) {
  EXPECT_FLOAT_EQ(ndviOf(3000.0f, 1000.0f), 0.5f);
  EXPECT_FLOAT_EQ(ndviOf(1000.0f, 1000.0f), 0.0f);
  EXPECT_FLOAT_EQ(ndviOf(0.0f, 500.0f), -1.0f);
  EXPECT_TRUE(std::isnan(ndviOf(0.0f, 0.0f)));       // nothing to divide by
  EXPECT_TRUE(std::isnan(ndviOf(-5.0f, 2.0f)));      // NIR + red ≤ 0
  EXPECT_TRUE(std::isnan(ndviOf(NAN, 2.0f)));
  EXPECT_TRUE(std::isnan(ndviOf(2.0f, NAN)));
  EXPECT_FLOAT_EQ(ndviOf(0.5f, -0.1f), 1.0f);        // a negative red: clamped to the range
}

TEST(NdviTileCodec, GreyPngRoundTripAndRgbRefused) {
  const fs::path d = freshDir("codec");
  ColorTile t;
  t.id = {12, 1, 2};
  t.ndvi.resize(256 * 256);
  for (size_t i = 0; i < t.ndvi.size(); ++i) t.ndvi[i] = static_cast<uint8_t>(i % 256);
  const fs::path p = ndviTilePath(d, t.id);
  EXPECT_EQ(p, d / "ndvi" / "12" / "1" / "2.png");
  ASSERT_TRUE(writeNdviTile(p, t));
  auto back = decodeNdviTile(fileBytesOf(p), t.id, p.string());
  ASSERT_TRUE(back) << back.error().message;
  EXPECT_EQ(*back, t.ndvi);
  auto read = readNdviTile(p, t.id);
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_EQ(*read, t.ndvi);

  // An RGB(A) PNG (an imagery tile) is not an NDVI tile.
  ColorTile rgb;
  rgb.id = t.id;
  rgb.rgba.assign(256 * 256 * 4, 200);
  const fs::path q = d / "rgb.png";
  ASSERT_TRUE(writeColorTile(q, rgb, ImageryFormat::Png));
  auto refused = decodeNdviTile(fileBytesOf(q), t.id, q.string());
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().kind, ErrorKind::InvalidInput);
  EXPECT_NE(refused.error().message.find(q.string()), std::string::npos) << refused.error().message;
  EXPECT_NE(refused.error().message.find("one-channel 8-bit PNG"), std::string::npos) << refused.error().message;

  // A grey PNG of the wrong size, and a JPEG.
  auto small = decodeNdviTile(fileBytesOf(p), t.id, p.string(), 512);
  ASSERT_FALSE(small);
  EXPECT_NE(small.error().message.find("is 256x256 pixels; dataset.json says tiles are 512 pixels a side"), std::string::npos) << small.error().message;
  const fs::path j = d / "rgb.jpg";
  ASSERT_TRUE(writeColorTile(j, rgb, ImageryFormat::Jpeg));
  EXPECT_FALSE(decodeNdviTile(fileBytesOf(j), t.id, j.string()));
  EXPECT_EQ(readNdviTile(d / "none.png", t.id).error().kind, ErrorKind::NotFound);
}

DatasetMeta sampleMeta() {
  DatasetMeta m;
  m.name = "zion";
  m.bounds = {-113.2396, 37.1321, -112.8521, 37.5129};
  m.minZoom = 9;
  m.maxZoom = 12;
  m.imagery = ImageryFormat::Jpeg;
  m.sources = {{"elevation", "srtm.tif", "WGS 84 (EPSG:4326)", "465x457"},
               {"nir", "landsat_b5.tif", "WGS 84 / UTM zone 12N (EPSG:32612)", "1128x1428"}};
  m.elevationTiles = 40;
  m.imageryTiles = 38;
  m.bytes = 12345;
  return m;
}

json metaJson(const fs::path& dir) {
  std::ifstream in(dir / "dataset.json");
  return json::parse(in);
}

TEST(NdviDatasetJson, RoundTripWithAndWithoutTheLayer) {
  const fs::path d = freshDir("with");
  DatasetMeta m = sampleMeta();
  m.ndvi = true;
  m.ndviTiles = 37;
  ASSERT_TRUE(writeDatasetMeta(d, m));
  const json j = metaJson(d);
  EXPECT_EQ(j["ndvi"]["encoding"], "ndvi8");
  EXPECT_EQ(j["ndvi"]["tiles"], "ndvi/{z}/{x}/{y}.png");
  EXPECT_EQ(j["ndvi"]["tile_count"], 37);
  auto back = readDatasetMeta(d);
  ASSERT_TRUE(back) << back.error().message;
  EXPECT_TRUE(back->ndvi);
  EXPECT_EQ(back->ndviTiles, 37u);
  EXPECT_EQ(back->sources[1].role, "nir");

  const fs::path e = freshDir("without");
  ASSERT_TRUE(writeDatasetMeta(e, sampleMeta()));
  EXPECT_TRUE(metaJson(e)["ndvi"].is_null());
  auto none = readDatasetMeta(e);
  ASSERT_TRUE(none) << none.error().message;
  EXPECT_FALSE(none->ndvi);
  EXPECT_EQ(none->ndviTiles, 0u);
}

TEST(NdviDatasetJson, MissingKeyReadsAsNoLayer) {
  // A dataset written before the layer existed has no "ndvi" key at all.
  const fs::path d = freshDir("old");
  ASSERT_TRUE(writeDatasetMeta(d, sampleMeta()));
  json j = metaJson(d);
  j.erase("ndvi");
  auto m = parseDatasetMeta(j.dump(), "old/dataset.json");
  ASSERT_TRUE(m) << m.error().message;
  EXPECT_FALSE(m->ndvi);
  EXPECT_EQ(m->imageryTiles, 38u);
}

TEST(NdviDatasetJson, MalformedFieldIsNamed) {
  const fs::path d = freshDir("bad");
  DatasetMeta meta = sampleMeta();
  meta.ndvi = true;
  ASSERT_TRUE(writeDatasetMeta(d, meta));
  const json good = metaJson(d);
  struct Case {
    json ndvi;
    std::string field;
  };
  const Case cases[] = {
      {json(5), "field 'ndvi' must be an object or null"},
      {json{{"tiles", "ndvi/{z}/{x}/{y}.png"}, {"tile_count", 1}}, "field 'ndvi.encoding' is missing"},
      {json{{"encoding", "ndvi16"}, {"tile_count", 1}}, "field 'ndvi.encoding' is 'ndvi16'; expected ndvi8"},
      {json{{"encoding", "ndvi8"}, {"tile_count", -1}}, "field 'ndvi.tile_count' is -1"},
      {json{{"encoding", "ndvi8"}}, "field 'ndvi.tile_count' is missing"},
  };
  for (const auto& c : cases) {
    json j = good;
    j["ndvi"] = c.ndvi;
    auto m = parseDatasetMeta(j.dump(), "x/dataset.json");
    ASSERT_FALSE(m) << c.ndvi.dump();
    EXPECT_EQ(m.error().kind, ErrorKind::InvalidInput);
    EXPECT_NE(m.error().message.find("'x/dataset.json'"), std::string::npos) << m.error().message;
    EXPECT_NE(m.error().message.find(c.field), std::string::npos) << m.error().message;
  }
}

TEST(NdviPyramid, ParentIsTheMeanOfValidChildValues) {
  const fs::path d = freshDir("pyramid");
  DatasetMeta meta;
  meta.minZoom = 8;
  meta.maxZoom = 10;
  meta.ndvi = true;
  // NDVI only in two children of 9/100/200 (NW 10/200/400 and SE 10/201/401), elevation only in
  // NW: the NDVI layer has its own tile set.
  for (const geo::TileId id : {geo::TileId{10, 200, 400}, geo::TileId{10, 201, 401}}) {
    ColorTile c;
    c.id = id;
    c.ndvi.resize(256 * 256);
    for (int y = 0; y < 256; ++y)
      for (int x = 0; x < 256; ++x) {
        // Column x holds NDVI (x − 128) / 200; pixel (1, 0) of every 2×2 block has none.
        c.ndvi[size_t(y) * 256 + size_t(x)] =
            (x % 2 == 1 && y % 2 == 0) ? 0 : ndviToByte(static_cast<float>(x - 128) / 200.0f);
      }
    ASSERT_TRUE(writeNdviTile(ndviTilePath(d, id), c));
  }
  HeightTile h;
  h.id = {10, 200, 400};
  h.heights.assign(256 * 256, 500.0f);
  ASSERT_TRUE(writeHeightTile(elevationTilePath(d, h.id), h, meta.elevationEncoding));
  NullProgress progress;
  ASSERT_TRUE(buildLowerZooms(d, meta, progress));
  EXPECT_EQ(meta.ndviTiles, 2u);  // 9/100/200 and 8/50/100
  EXPECT_EQ(meta.elevationTiles, 2u);
  EXPECT_EQ(meta.imageryTiles, 0u);

  auto p = readNdviTile(ndviTilePath(d, {9, 100, 200}), {9, 100, 200});
  ASSERT_TRUE(p) << p.error().message;
  // NW quadrant pixel (i, j) ← child columns 2i (twice) and 2i + 1 (once): the mean of their
  // decoded values.
  for (int i : {3, 40, 100}) {
    const float a = ndviFromByte(ndviToByte(static_cast<float>(2 * i - 128) / 200.0f));
    const float b = ndviFromByte(ndviToByte(static_cast<float>(2 * i + 1 - 128) / 200.0f));
    EXPECT_EQ((*p)[size_t(10) * 256 + size_t(i)], ndviToByte((2 * a + b) / 3.0f)) << i;
  }
  EXPECT_EQ((*p)[size_t(10) * 256 + 200], 0);  // NE child missing: no NDVI
  EXPECT_NE((*p)[size_t(200) * 256 + 200], 0);  // SE child present
  auto top = readNdviTile(ndviTilePath(d, {8, 50, 100}), {8, 50, 100});
  ASSERT_TRUE(top) << top.error().message;
  EXPECT_NE((*top)[size_t(5) * 256 + 5], 0);
}

}  // namespace
}  // namespace vegstream::datasets
