// The landcover layer's parts without an import (landcover.h, dataset_format.h,
// pyramid_builder.h): the tile codec, nearest-class sampling of a hand-made raster (never a
// blend), the raster check and histogram, the 2×2 mode, the pyramid over hand-made child tiles,
// and the "landcover" field of dataset.json.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>

#include <nlohmann/json.hpp>

#include "datasets/dataset_format.h"
#include "datasets/landcover.h"
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

TEST(LandcoverTileCodec, GreyPngRoundTripAndOtherImagesRefused) {
  const fs::path d = freshDir("codec");
  LandcoverTile t;
  t.id = {13, 5, 7};
  t.classes.resize(256 * 256);
  for (size_t i = 0; i < t.classes.size(); ++i) t.classes[i] = static_cast<uint8_t>((i * 7) % 256);  // every byte
  const fs::path p = landcoverTilePath(d, t.id);
  EXPECT_EQ(p, d / "landcover" / "13" / "5" / "7.png");
  ASSERT_TRUE(writeLandcoverTile(p, t));
  auto back = readLandcoverTile(p, t.id);
  ASSERT_TRUE(back) << back.error().message;
  EXPECT_EQ(back->classes, t.classes);
  EXPECT_EQ(back->size, 256);
  EXPECT_EQ(back->id, t.id);
  EXPECT_EQ(back->at(3, 0), t.classes[3]);
  auto decoded = decodeLandcoverTile(fileBytesOf(p), t.id, "mem");
  ASSERT_TRUE(decoded) << decoded.error().message;
  EXPECT_EQ(decoded->classes, t.classes);

  // An RGBA PNG, a JPEG, another size, a truncated file, a missing one.
  ColorTile rgb;
  rgb.id = t.id;
  rgb.rgba.assign(256 * 256 * 4, 10);
  const fs::path q = d / "rgb.png", j = d / "rgb.jpg";
  ASSERT_TRUE(writeColorTile(q, rgb, ImageryFormat::Png));
  ASSERT_TRUE(writeColorTile(j, rgb, ImageryFormat::Jpeg));
  auto refused = readLandcoverTile(q, t.id);
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().kind, ErrorKind::InvalidInput);
  EXPECT_NE(refused.error().message.find(q.string()), std::string::npos) << refused.error().message;
  EXPECT_NE(refused.error().message.find("landcover layer: expected a one-channel 8-bit PNG"), std::string::npos)
      << refused.error().message;
  EXPECT_FALSE(readLandcoverTile(j, t.id));
  auto wide = readLandcoverTile(p, t.id, 512);
  ASSERT_FALSE(wide);
  EXPECT_NE(wide.error().message.find("is 256x256 pixels; dataset.json says tiles are 512 pixels a side"), std::string::npos)
      << wide.error().message;
  std::vector<uint8_t> cut = fileBytesOf(p);
  cut.resize(cut.size() / 2);
  auto truncated = decodeLandcoverTile(cut, t.id, "cut.png");
  ASSERT_FALSE(truncated);
  EXPECT_EQ(truncated.error().kind, ErrorKind::InvalidInput);
  EXPECT_NE(truncated.error().message.find("cut.png"), std::string::npos) << truncated.error().message;
  EXPECT_EQ(readLandcoverTile(d / "none.png", t.id).error().kind, ErrorKind::NotFound);
}

// A 4 × 2 class raster: columns 10 | 30 | 40 | nodata (255), second row 20 | 20 | 0 | 7.5.
Raster classRaster() {
  Raster r;
  r.path = "lc.tif";
  r.width = 4;
  r.height = 2;
  r.channels = 1;
  r.samples = {10, 30, 40, 255, 20, 20, 0, 7.5f};
  r.nodata = 255.0;
  return r;
}

TEST(LandcoverSampling, NearestClassNeverBlends) {
  const Raster r = classRaster();
  EXPECT_EQ(nearestClass(r, {0.5, 0.5}), 10);  // pixel centres
  EXPECT_EQ(nearestClass(r, {1.5, 0.5}), 30);
  EXPECT_EQ(nearestClass(r, {0.5, 1.5}), 20);
  // On the edge between 10 and 30, and just either side of it: one of the two, never 20 (their
  // mean) or anything else.
  EXPECT_EQ(nearestClass(r, {1.0, 0.5}), 30);  // a shared edge goes to the pixel right of it
  EXPECT_EQ(nearestClass(r, {1.0 - 1e-9, 0.5}), 10);
  EXPECT_EQ(nearestClass(r, {1.0 + 1e-9, 0.25}), 30);
  // The corner of four pixels (10, 30, 20, 20): the pixel below-right of it.
  EXPECT_EQ(nearestClass(r, {1.0, 1.0}), 20);
  for (double x = 0.0; x < 2.0; x += 0.01) {
    const uint8_t c = nearestClass(r, {x, 0.3});
    EXPECT_TRUE(c == 10 || c == 30) << x << " gave " << int(c);
    EXPECT_EQ(c, x < 1.0 ? 10 : 30) << x;
  }
  EXPECT_EQ(nearestClass(r, {3.5, 0.5}), 0);    // nodata
  EXPECT_EQ(nearestClass(r, {2.5, 1.5}), 0);    // 0 as stored is no data
  EXPECT_EQ(nearestClass(r, {3.5, 1.5}), 0);    // not an integer: no class
  EXPECT_EQ(nearestClass(r, {-0.01, 0.5}), 0);  // outside
  EXPECT_EQ(nearestClass(r, {4.0, 0.5}), 0);
  EXPECT_EQ(nearestClass(r, {0.5, 2.0}), 0);
  EXPECT_EQ(nearestClass(r, {NAN, 0.5}), 0);

  // A window of a larger raster (raster.h): pixels are whole-raster coordinates.
  Raster w = classRaster();
  w.origin = {100.0, 50.0};
  EXPECT_EQ(nearestClass(w, {101.5, 50.5}), 30);
  EXPECT_EQ(nearestClass(w, {100.999, 51.2}), 20);
  EXPECT_EQ(nearestClass(w, {1.5, 0.5}), 0);  // outside the window
  auto bad = checkClassRaster(w);
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("holds 7.5 at column 103, row 51"), std::string::npos) << bad.error().message;
  // Decimated by 2: buffer pixel (1, 0) stands for whole-raster pixels 102 … 103.
  w.step = {2.0, 2.0};
  EXPECT_EQ(nearestClass(w, {103.9, 51.9}), 30);
  EXPECT_EQ(nearestClass(w, {104.0, 50.0}), 40);
}

TEST(LandcoverSampling, RasterCheckAndHistogram) {
  Raster r = classRaster();
  auto bad = checkClassRaster(r);
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().kind, ErrorKind::InvalidInput);
  EXPECT_NE(bad.error().message.find("'lc.tif' holds 7.5 at column 3, row 1"), std::string::npos)
      << bad.error().message;
  r.samples[7] = 300.0f;
  EXPECT_FALSE(checkClassRaster(r));
  r.samples[7] = 7.0f;
  EXPECT_TRUE(checkClassRaster(r));
  Raster rgb = r;
  rgb.channels = 2;
  rgb.width = 2;
  auto twoBands = checkClassRaster(rgb);
  ASSERT_FALSE(twoBands);
  EXPECT_NE(twoBands.error().message.find("has 2 bands"), std::string::npos) << twoBands.error().message;

  const ClassHistogram h = classHistogram(r);
  EXPECT_EQ(h[0], 2u);  // nodata 255 and the stored 0
  EXPECT_EQ(h[10], 1u);
  EXPECT_EQ(h[20], 2u);
  EXPECT_EQ(h[30], 1u);
  EXPECT_EQ(h[40], 1u);
  EXPECT_EQ(h[7], 1u);
  EXPECT_EQ(h[255], 0u);
  uint64_t total = 0;
  for (uint64_t n : h) total += n;
  EXPECT_EQ(total, 8u);
}

TEST(LandcoverMode, MostFrequentClassTiesToTheSmallest) {
  auto mode = [](std::vector<uint8_t> v) { return int(modeOfClasses(v)); };
  EXPECT_EQ(mode({10, 10, 30, 40}), 10);
  EXPECT_EQ(mode({40, 30, 30, 10}), 30);
  EXPECT_EQ(mode({40, 30, 20, 90}), 20);  // all different: the smallest
  EXPECT_EQ(mode({90, 90, 20, 20}), 20);  // a tie
  EXPECT_EQ(mode({0, 0, 0, 50}), 50);     // no data never wins
  EXPECT_EQ(mode({0, 0, 95, 11}), 11);
  EXPECT_EQ(mode({0, 0, 0, 0}), 0);
  EXPECT_EQ(mode({}), 0);
  EXPECT_EQ(mode({255, 255, 254}), 255);
}

// Child tiles 10/200/400 (NW) and 10/201/400 (NE) of 9/100/200; each 2×2 block of NW holds
// (10, 10, 30, 40), of NE (90, 20, 20, 90) with one no-data pixel in every fourth block.
void writeChildren(const fs::path& d) {
  for (const geo::TileId id : {geo::TileId{10, 200, 400}, geo::TileId{10, 201, 400}}) {
    LandcoverTile t;
    t.id = id;
    t.classes.resize(256 * 256);
    const bool nw = id.x == 200;
    for (int y = 0; y < 256; ++y)
      for (int x = 0; x < 256; ++x) {
        const int k = (y % 2) * 2 + (x % 2);
        uint8_t c =
            nw ? std::array<uint8_t, 4>{10, 10, 30, 40}[size_t(k)] : std::array<uint8_t, 4>{90, 20, 20, 90}[size_t(k)];
        if (!nw && k == 0 && (x / 2) % 4 == 3) c = 0;  // (0, 20, 20, 90): 20 wins outright
        t.classes[size_t(y) * 256 + size_t(x)] = c;
      }
    ASSERT_TRUE(writeLandcoverTile(landcoverTilePath(d, id), t));
  }
}

TEST(LandcoverPyramid, ParentIsTheModeOfItsChildrensClasses) {
  const fs::path d = freshDir("pyramid");
  DatasetMeta meta;
  meta.minZoom = 8;
  meta.maxZoom = 10;
  meta.landcover = LandcoverScheme::WorldCover;
  writeChildren(d);
  NullProgress progress;
  ASSERT_TRUE(buildLowerZooms(d, meta, progress));
  EXPECT_EQ(meta.landcoverTiles, 2u);  // 9/100/200 and 8/50/100
  EXPECT_EQ(meta.elevationTiles, 0u);
  EXPECT_GT(meta.bytes, 0u);

  auto p = readLandcoverTile(landcoverTilePath(d, {9, 100, 200}), {9, 100, 200});
  ASSERT_TRUE(p) << p.error().message;
  std::set<int> seen;
  for (int y = 0; y < 256; ++y) {
    for (int x = 0; x < 256; ++x) {
      const int c = p->at(x, y);
      seen.insert(c);
      // SW, SE children missing: no data; NW (10, 10, 30, 40) → 10; NE (90, 20, 20, 90) → tie → 20.
      const int expected = y >= 128 ? 0 : x < 128 ? 10 : 20;
      EXPECT_EQ(c, expected) << x << "," << y;
    }
  }
  EXPECT_EQ(seen, (std::set<int>{0, 10, 20}));  // nothing that is no child's class (no mean: 25, 55)

  // Zoom 8 from zoom 9 alone (its other three children are missing).
  auto top = readLandcoverTile(landcoverTilePath(d, {8, 50, 100}), {8, 50, 100});
  ASSERT_TRUE(top) << top.error().message;
  EXPECT_EQ(top->at(10, 10), 10);
  EXPECT_EQ(top->at(63, 10), 10);
  EXPECT_EQ(top->at(64, 10), 20);
  EXPECT_EQ(top->at(100, 10), 20);
  EXPECT_EQ(top->at(10, 100), 0);  // zoom 9's missing rows
  EXPECT_EQ(top->at(200, 10), 0);  // 9/101/200 missing
}

DatasetMeta sampleMeta() {
  DatasetMeta m;
  m.name = "lc";
  m.bounds = {-113.2396, 37.1321, -112.8521, 37.5129};
  m.minZoom = 9;
  m.maxZoom = 12;
  m.sources = {{"elevation", "srtm.tif", "WGS 84 (EPSG:4326)", "465x457"},
               {"landcover", "worldcover.tif", "WGS 84 (EPSG:4326)", "3600x3600"}};
  m.elevationTiles = 40;
  m.bytes = 999;
  return m;
}

json metaJson(const fs::path& dir) {
  std::ifstream in(dir / "dataset.json");
  return json::parse(in);
}

TEST(LandcoverDatasetJson, RoundTripWithAndWithoutTheLayer) {
  for (LandcoverScheme s : {LandcoverScheme::WorldCover, LandcoverScheme::Nlcd}) {
    const fs::path d = freshDir(std::string("with_") + toString(s));
    DatasetMeta m = sampleMeta();
    m.landcover = s;
    m.landcoverTiles = 41;
    ASSERT_TRUE(writeDatasetMeta(d, m));
    const json j = metaJson(d);
    EXPECT_EQ(j["landcover"]["encoding"], "class8");
    EXPECT_EQ(j["landcover"]["scheme"], toString(s));
    EXPECT_EQ(j["landcover"]["tiles"], "landcover/{z}/{x}/{y}.png");
    EXPECT_EQ(j["landcover"]["tile_count"], 41);
    auto back = readDatasetMeta(d);
    ASSERT_TRUE(back) << back.error().message;
    EXPECT_EQ(back->landcover, std::optional(s));
    EXPECT_EQ(back->landcoverTiles, 41u);
    EXPECT_EQ(back->sources[1].role, "landcover");
  }
  const fs::path e = freshDir("without");
  ASSERT_TRUE(writeDatasetMeta(e, sampleMeta()));
  EXPECT_TRUE(metaJson(e)["landcover"].is_null());
  auto none = readDatasetMeta(e);
  ASSERT_TRUE(none) << none.error().message;
  EXPECT_FALSE(none->landcover);
  EXPECT_EQ(none->landcoverTiles, 0u);
  // Written before the layer existed: no key at all.
  json old = metaJson(e);
  old.erase("landcover");
  auto m = parseDatasetMeta(old.dump(), "old/dataset.json");
  ASSERT_TRUE(m) << m.error().message;
  EXPECT_FALSE(m->landcover);
  EXPECT_EQ(m->elevationTiles, 40u);
}

TEST(LandcoverDatasetJson, MalformedFieldIsNamed) {
  const fs::path d = freshDir("bad");
  DatasetMeta meta = sampleMeta();
  meta.landcover = LandcoverScheme::Nlcd;
  ASSERT_TRUE(writeDatasetMeta(d, meta));
  const json good = metaJson(d);
  const json lc = good["landcover"];
  auto with = [&](const char* key, json v) {
    json o = lc;
    if (v.is_discarded()) {
      o.erase(key);
    } else {
      o[key] = v;
    }
    return o;
  };
  const json gone(json::value_t::discarded);
  const std::pair<json, std::string> cases[] = {
      {json("nlcd"), "field 'landcover' must be an object or null"},
      {with("encoding", gone), "field 'landcover.encoding' is missing"},
      {with("encoding", "ndvi8"), "field 'landcover.encoding' is 'ndvi8'; expected class8"},
      {with("scheme", gone), "field 'landcover.scheme' is missing"},
      {with("scheme", 3), "field 'landcover.scheme' must be a string"},
      {with("scheme", "auto"), "field 'landcover.scheme' is 'auto'; expected worldcover or nlcd"},
      {with("scheme", "corine"), "field 'landcover.scheme' is 'corine'"},
      {with("tile_count", -2), "field 'landcover.tile_count' is -2"},
      {with("tile_count", gone), "field 'landcover.tile_count' is missing"},
  };
  for (const auto& [value, field] : cases) {
    json j = good;
    j["landcover"] = value;
    auto m = parseDatasetMeta(j.dump(), "x/dataset.json");
    ASSERT_FALSE(m) << value.dump();
    EXPECT_EQ(m.error().kind, ErrorKind::InvalidInput);
    EXPECT_NE(m.error().message.find("'x/dataset.json'"), std::string::npos) << m.error().message;
    EXPECT_NE(m.error().message.find(field), std::string::npos) << m.error().message;
  }
}

}  // namespace
}  // namespace vegstream::datasets
