// The landcover layer read back: DatasetReader::landcoverAt, `vegstream query` and `vegstream
// info` on a small synthetic dataset to which the test adds landcover tiles it makes itself —
// at the max zoom a pattern around the dataset's centre pixel (10 west of it, 30 east of it, no
// data south of it, one unknown code 7), at the zoom below a uniform 40 — so every expected
// class is known by construction.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include <nlohmann/json.hpp>

#include "datasets/dataset_reader.h"
#include "datasets/landcover.h"
#include "datasets/synthetic_generator.h"
#include "tests/support/run_command.h"
#include "tests/support/test_dirs.h"

namespace vegstream::testing {
namespace {
namespace fs = std::filesystem;
using datasets::LandcoverTile;
using nlohmann::json;

constexpr int kMaxZoom = 13;

std::string q(const fs::path& p) { return "'" + p.string() + "'"; }

struct Synthetic {
  fs::path dir;
  datasets::DatasetMeta meta;
  int64_t cx = 0, cy = 0;  // the centre's global pixel at kMaxZoom
};

// Class of global pixel (gx, gy) at kMaxZoom in the hand-made layer.
uint8_t classAt(const Synthetic& s, int64_t gx, int64_t gy) {
  if (gy > s.cy + 10) return 0;
  if (gx == s.cx + 5 && gy == s.cy - 5) return 7;
  return gx < s.cx ? 10 : 30;
}

// The lon/lat of global pixel coordinates (continuous, corner-based) at zoom z.
glm::dvec2 lonLatOf(double gx, double gy, int z) { return geo::tileXYToLonLat({gx / 256.0, gy / 256.0}, z); }

Synthetic makeDataset(const fs::path& dir) {
  datasets::SyntheticOptions o;
  o.out = dir;
  o.name = "landcover";
  o.sizeKm = 1.0;
  o.maxZoom = kMaxZoom;
  o.minZoom = kMaxZoom - 1;
  o.threads = 1;
  datasets::NullProgress progress;
  auto meta = datasets::generateSyntheticDataset(o, makeNullLogger(), progress);
  EXPECT_TRUE(meta) << meta.error().message;
  Synthetic s{dir, meta ? *meta : datasets::DatasetMeta{}};
  const glm::dvec2 c = geo::lonLatToTileXY({o.centreLonDeg, o.centreLatDeg}, kMaxZoom);
  s.cx = static_cast<int64_t>(std::floor(c.x * 256.0));
  s.cy = static_cast<int64_t>(std::floor(c.y * 256.0));
  return s;
}

// Landcover tiles over every elevation tile of the two zooms, and the layer in dataset.json.
void addLandcover(Synthetic& s) {
  for (const auto& xdir : fs::directory_iterator(s.dir / "elevation" / std::to_string(kMaxZoom)))
    for (const auto& file : fs::directory_iterator(xdir.path())) {
      const geo::TileId id{kMaxZoom, std::stoi(xdir.path().filename().string()),
                           std::stoi(file.path().stem().string())};
      LandcoverTile t;
      t.id = id;
      t.classes.resize(256 * 256);
      for (int j = 0; j < 256; ++j)
        for (int i = 0; i < 256; ++i)
          t.classes[size_t(j) * 256 + size_t(i)] = classAt(s, int64_t{id.x} * 256 + i, int64_t{id.y} * 256 + j);
      ASSERT_TRUE(datasets::writeLandcoverTile(datasets::landcoverTilePath(s.dir, id), t));
      ++s.meta.landcoverTiles;
      const geo::TileId up = geo::parent(id);
      if (fs::exists(datasets::landcoverTilePath(s.dir, up))) continue;
      LandcoverTile coarse;
      coarse.id = up;
      coarse.classes.assign(256 * 256, 40);
      ASSERT_TRUE(datasets::writeLandcoverTile(datasets::landcoverTilePath(s.dir, up), coarse));
      ++s.meta.landcoverTiles;
    }
  s.meta.landcover = datasets::LandcoverScheme::WorldCover;
  ASSERT_TRUE(datasets::writeDatasetMeta(s.dir, s.meta));
}

class LandcoverQuery : public ::testing::Test {
 protected:
  void SetUp() override {
    s_ = makeDataset(testOutputDir() / "synth");
    ASSERT_TRUE(fs::exists(s_.dir / "dataset.json"));
  }
  // landcoverAt at global pixel coordinates (gx, gy) of kMaxZoom.
  std::optional<uint8_t> at(datasets::DatasetReader& r, double gx, double gy) {
    const glm::dvec2 p = lonLatOf(gx, gy, kMaxZoom);
    auto c = r.landcoverAt(p.y, p.x);
    EXPECT_TRUE(c) << c.error().message;
    return c ? *c : std::nullopt;
  }
  json query(double gx, double gy) {
    const glm::dvec2 p = lonLatOf(gx, gy, kMaxZoom);
    char args[128];
    std::snprintf(args, sizeof(args), " --lat %.12f --lon %.12f", p.y, p.x);
    const auto r = runVegstream("query " + q(s_.dir) + args);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return r.exitCode == 0 ? json::parse(r.out) : json();
  }
  Synthetic s_;
};

TEST_F(LandcoverQuery, ReaderGivesTheNearestPixelsClassAtTheFinestZoomWithData) {
  const double cx = static_cast<double>(s_.cx), cy = static_cast<double>(s_.cy);
  {  // Before the layer: no landcover anywhere, and query says null.
    auto r = datasets::DatasetReader::open(s_.dir);
    ASSERT_TRUE(r) << r.error().message;
    EXPECT_EQ(at(*r, cx - 3.5, cy - 3.5), std::nullopt);
    EXPECT_TRUE(query(cx - 3.5, cy - 3.5)["landcover"].is_null());
  }
  addLandcover(s_);
  auto r = datasets::DatasetReader::open(s_.dir);
  ASSERT_TRUE(r) << r.error().message;
  ASSERT_EQ(r->meta().landcover, std::optional(datasets::LandcoverScheme::WorldCover));
  EXPECT_EQ(at(*r, cx - 3.5, cy - 3.5), std::optional<uint8_t>(10));
  EXPECT_EQ(at(*r, cx + 2.5, cy - 3.5), std::optional<uint8_t>(30));
  // Either side of the edge between a 10 and a 30 pixel: one of them, never a blend.
  EXPECT_EQ(at(*r, cx - 0.02, cy + 0.5), std::optional<uint8_t>(10));
  EXPECT_EQ(at(*r, cx + 0.02, cy + 0.5), std::optional<uint8_t>(30));
  EXPECT_EQ(at(*r, cx + 5.5, cy - 4.5), std::optional<uint8_t>(7));  // as stored, unknown or not
  // No data at the max zoom there: the zoom below has 40.
  EXPECT_EQ(at(*r, cx - 3.5, cy + 20.5), std::optional<uint8_t>(40));
  // Outside the dataset: none.
  auto outside = r->landcoverAt(r->meta().bounds.northDeg + 0.01, r->meta().bounds.westDeg);
  ASSERT_TRUE(outside);
  EXPECT_EQ(*outside, std::nullopt);
}

TEST_F(LandcoverQuery, QueryPrintsTheClassAndInfoCountsTheTiles) {
  addLandcover(s_);
  const double cx = static_cast<double>(s_.cx), cy = static_cast<double>(s_.cy);
  const json tree = query(cx - 3.5, cy - 3.5)["landcover"];
  EXPECT_EQ(tree, (json{{"code", 10}, {"name", "Tree cover"}, {"kind", "tree"}, {"scheme", "worldcover"}}));
  const json grass = query(cx + 2.5, cy - 3.5)["landcover"];
  EXPECT_EQ(grass, (json{{"code", 30}, {"name", "Grassland"}, {"kind", "grass"}, {"scheme", "worldcover"}}));
  const json crop = query(cx - 3.5, cy + 20.5)["landcover"];
  EXPECT_EQ(crop["code"], 40);
  EXPECT_EQ(crop["kind"], "crop");
  const json unknown = query(cx + 5.5, cy - 4.5)["landcover"];
  EXPECT_EQ(unknown, (json{{"code", 7}, {"name", nullptr}, {"kind", nullptr}, {"scheme", "worldcover"}}));

  const auto info = runVegstream("info " + q(s_.dir));
  ASSERT_EQ(info.exitCode, 0) << info.err;
  EXPECT_EQ(info.err.find("landcover tiles"), std::string::npos) << info.err;  // counts agree
  const json j = json::parse(info.out);
  EXPECT_EQ(j["landcover_scheme"], "worldcover");
  EXPECT_EQ(j["tiles"]["landcover"], s_.meta.landcoverTiles);
  EXPECT_EQ(j["tiles"]["on_disk"]["landcover"], s_.meta.landcoverTiles);
  uint64_t perZoom = 0;
  for (const json& z : j["tiles"]["per_zoom"]) {
    EXPECT_TRUE(z.contains("landcover")) << z.dump();
    perZoom += z.value("landcover", uint64_t{0});
  }
  EXPECT_EQ(perZoom, s_.meta.landcoverTiles);
  EXPECT_GE(s_.meta.landcoverTiles, 2u);
}

TEST_F(LandcoverQuery, InfoWithoutTheLayerAndACorruptTile) {
  const auto before = runVegstream("info " + q(s_.dir));
  ASSERT_EQ(before.exitCode, 0) << before.err;
  const json j = json::parse(before.out);
  EXPECT_TRUE(j["landcover_scheme"].is_null());
  EXPECT_TRUE(j["tiles"]["landcover"].is_null());

  addLandcover(s_);
  const geo::TileId id{kMaxZoom, static_cast<int>(s_.cx / 256), static_cast<int>(s_.cy / 256)};
  const fs::path tile = datasets::landcoverTilePath(s_.dir, id);
  ASSERT_TRUE(fs::exists(tile));
  std::ofstream(tile, std::ios::binary | std::ios::trunc) << "not a png";
  const glm::dvec2 p = lonLatOf(static_cast<double>(s_.cx) - 3.5, static_cast<double>(s_.cy) - 3.5, kMaxZoom);
  char args[128];
  std::snprintf(args, sizeof(args), " --lat %.12f --lon %.12f", p.y, p.x);
  const auto r = runVegstream("query " + q(s_.dir) + args);
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_EQ(countLines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(tile.string()), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

}  // namespace
}  // namespace vegstream::testing
