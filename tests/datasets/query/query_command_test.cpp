// `vegstream info` and `vegstream query` on the imported grandcanyon-xyz sample, the reader's
// bilinear interpolation checked by hand, and the user mistakes (exit 2, one message).

#include <cmath>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "datasets/dataset_reader.h"
#include "datasets/tile_codec.h"
#include "tests/datasets/query/query_fixture.h"

namespace vegstream::testing {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;

std::string q(const fs::path& p) { return "'" + p.string() + "'"; }

// Bilinear by hand from the four source pixels (terrain-RGB files of the sample) around a point.
double handBilinear(double lat, double lon) {
  const glm::dvec2 t = geo::lonLatToTileXY({lon, lat}, 12);
  const double gx = t.x * 256.0 - 0.5, gy = t.y * 256.0 - 0.5;
  const double x0 = std::floor(gx), y0 = std::floor(gy), fx = gx - x0, fy = gy - y0;
  auto pixel = [](long gxi, long gyi) {
    const int tx = static_cast<int>(gxi / 256), ty = static_cast<int>(gyi / 256);
    const geo::TileId id{12, tx, ty};
    auto tile = datasets::readHeightTile(
        grandCanyonDir() / "terrain-rgb/12" / std::to_string(tx) / (std::to_string(ty) + ".png"), id,
        datasets::ElevationEncoding::TerrainRgb, datasets::kTileSize);
    EXPECT_TRUE(tile.ok());
    return double{tile->at(static_cast<int>(gxi - tx * 256L), static_cast<int>(gyi - ty * 256L))};
  };
  const long ix = static_cast<long>(x0), iy = static_cast<long>(y0);
  return (1 - fx) * (1 - fy) * pixel(ix, iy) + fx * (1 - fy) * pixel(ix + 1, iy) + (1 - fx) * fy * pixel(ix, iy + 1) +
         fx * fy * pixel(ix + 1, iy + 1);
}

TEST_F(GrandCanyon, InfoReportsTheDataset) {
  const auto r = runVegstream("info " + q(dir()));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["name"], "grandcanyon");
  EXPECT_NEAR(j["bounds"]["west"].get<double>(), -113.3789, 1e-4);
  EXPECT_NEAR(j["bounds"]["east"].get<double>(), -113.2031, 1e-4);
  EXPECT_NEAR(j["bounds"]["south"].get<double>(), 35.8891, 1e-4);
  EXPECT_NEAR(j["bounds"]["north"].get<double>(), 36.0313, 1e-4);
  EXPECT_EQ(j["zoom"]["min"], 11);
  EXPECT_EQ(j["zoom"]["max"], 12);
  EXPECT_EQ(j["tiles"]["elevation"], 5);
  EXPECT_EQ(j["tiles"]["imagery"], 5);
  EXPECT_EQ(j["tiles"]["per_zoom"].size(), 2u);
  EXPECT_EQ(j["tiles"]["per_zoom"][1]["elevation"], 4);
  EXPECT_NEAR(j["height_m"]["min"].get<double>(), 439.0, 0.5);
  EXPECT_NEAR(j["height_m"]["max"].get<double>(), 2184.0, 0.5);
  EXPECT_EQ(j["crs"]["sources"][0], "WGS 84 / Pseudo-Mercator (EPSG:3857)");
  EXPECT_GT(j["bytes"].get<uint64_t>(), 10000u);
  EXPECT_EQ(j["bytes"], j["bytes_on_disk"]);
}

TEST_F(GrandCanyon, QueryMatchesHandBilinear) {
  // The centre of the four tiles (their shared corner: the four pixels lie in four tiles) and a
  // point inside one tile.
  const glm::dvec2 corner = geo::tileXYToLonLat({759.0, 1609.0}, 12);
  const glm::dvec2 inside = geo::tileXYToLonLat({759.3137, 1608.7071}, 12);
  for (const glm::dvec2& p : {corner, inside}) {
    const auto r =
        runVegstream("query " + q(dir()) + " --lat " + std::to_string(p.y) + " --lon " + std::to_string(p.x));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const json j = json::parse(r.out);
    const double h = j["height_m"].get<double>();
    EXPECT_GE(h, 439.0);
    EXPECT_LE(h, 2184.0);
    // std::to_string printed 6 decimals: evaluate by hand at the same rounded point.
    const double lat = std::stod(std::to_string(p.y)), lon = std::stod(std::to_string(p.x));
    EXPECT_NEAR(h, handBilinear(lat, lon), 1e-3);
    ASSERT_TRUE(j["color"].is_object());
    EXPECT_EQ(j["color"]["hex"].get<std::string>().size(), 7u);
  }
}

TEST_F(GrandCanyon, ReaderBilinearAndCache) {
  auto reader = datasets::DatasetReader::open(dir(), 8);
  ASSERT_TRUE(reader.ok()) << reader.error().message;
  double maxDiff = 0.0;
  for (int k = 0; k < 200; ++k) {  // a deterministic walk over the whole area
    const double fx = 0.02 + 0.96 * std::fmod(k * 0.618034, 1.0), fy = 0.02 + 0.96 * std::fmod(k * 0.414214, 1.0);
    const glm::dvec2 p = geo::tileXYToLonLat({758.0 + 2.0 * fx, 1608.0 + 2.0 * fy}, 12);
    auto h = reader->heightAt(p.y, p.x);
    ASSERT_TRUE(h.ok()) << h.error().message;
    maxDiff = std::max(maxDiff, std::abs(*h - handBilinear(p.y, p.x)));
  }
  EXPECT_LE(maxDiff, 1e-3);
  EXPECT_LE(reader->tilesDecoded(), 40u);  // 4 tiles, an LRU of 8: no decode per query
}

TEST_F(GrandCanyon, QueryOutsideBoundsIsAUserError) {
  const auto r = runVegstream("query " + q(dir()) + " --lat 36.5 --lon -113.3");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_EQ(countLines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("outside"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty());
}

TEST_F(GrandCanyon, BadFieldInDatasetJsonIsNamed) {
  const fs::path copy = testTmp("badfield");
  fs::create_directories(copy);
  std::ifstream in(dir() / "dataset.json");
  json j = json::parse(in);
  j["max_zoom"] = "twelve";
  std::ofstream(copy / "dataset.json") << j.dump(2);
  for (const std::string& cmd : {"info " + q(copy), "query " + q(copy) + " --lat 35.95 --lon -113.3"}) {
    const auto r = runVegstream(cmd);
    EXPECT_EQ(r.exitCode, 2) << cmd;
    EXPECT_EQ(countLines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("max_zoom"), std::string::npos) << r.err;
  }
  fs::remove_all(copy);
}

// A dataset without the NDVI layer (no --imagery-nir), and one written before the layer existed
// (no "ndvi" nor "landcover" key in dataset.json): query prints "ndvi": null, "landcover": null
// and everything else as before.
TEST_F(GrandCanyon, QueryWithoutNdviLayerPrintsNull) {
  const fs::path old = testTmp("no_ndvi_key");
  fs::copy(dir(), old, fs::copy_options::recursive);
  json meta;
  {
    std::ifstream in(old / "dataset.json");
    meta = json::parse(in);
  }
  EXPECT_TRUE(meta.contains("ndvi") && meta["ndvi"].is_null());
  EXPECT_TRUE(meta.contains("landcover") && meta["landcover"].is_null());
  meta.erase("ndvi");
  meta.erase("landcover");  // nor a landcover layer (issue 40)
  std::ofstream(old / "dataset.json") << meta.dump(2);

  const glm::dvec2 p = geo::tileXYToLonLat({759.3137, 1608.7071}, 12);
  const std::string at = " --lat " + std::to_string(p.y) + " --lon " + std::to_string(p.x);
  const auto now = runVegstream("query " + q(dir()) + at), before = runVegstream("query " + q(old) + at);
  ASSERT_EQ(now.exitCode, 0) << now.err;
  ASSERT_EQ(before.exitCode, 0) << before.err;
  const json j = json::parse(now.out);
  EXPECT_TRUE(j.contains("ndvi") && j["ndvi"].is_null()) << now.out;
  EXPECT_TRUE(j.contains("landcover") && j["landcover"].is_null()) << now.out;
  EXPECT_TRUE(j.contains("canopy_height_m") && j["canopy_height_m"].is_null()) << now.out;
  EXPECT_EQ(json::parse(before.out), j);
  std::vector<std::string> keys;
  for (const auto& [k, v] : j.items()) keys.push_back(k);
  // excess_green: the calibrated colour's ExG the species choice used; canopy_cover: the share of
  // the two best species that are trees (issue 41).
  EXPECT_EQ(keys, (std::vector<std::string>{"canopy_cover", "canopy_height_m", "color", "dataset", "excess_green", "height_m",
                                            "landcover", "lat", "lon", "ndvi", "species", "species_bare",
                                            "species_candidates"}));
  auto reader = datasets::DatasetReader::open(dir());
  ASSERT_TRUE(reader.ok());
  const double lat = std::stod(std::to_string(p.y)), lon = std::stod(std::to_string(p.x));
  EXPECT_NEAR(j["height_m"].get<double>(), *reader->heightAt(lat, lon), 1e-9);
  const auto colour = reader->colorAt(lat, lon);
  ASSERT_TRUE(colour.ok() && colour->has_value());
  EXPECT_EQ(j["color"]["r"].get<int>(), (**colour)[0]);
  auto ndvi = reader->ndviAt(lat, lon);
  ASSERT_TRUE(ndvi.ok());
  EXPECT_FALSE(ndvi->has_value());

  const auto info = runVegstream("info " + q(old));
  ASSERT_EQ(info.exitCode, 0) << info.err;
  EXPECT_TRUE(json::parse(info.out)["tiles"]["ndvi"].is_null());
  EXPECT_EQ(info.err.find("NDVI"), std::string::npos) << info.err;  // no count mismatch warned
}

TEST(QueryCommand, MissingDatasetIsAUserError) {
  const fs::path missing = testOutputDir() / "no_such_dataset";
  for (const std::string& cmd : {"info " + q(missing), "query " + q(missing) + " --lat 1 --lon 2"}) {
    const auto r = runVegstream(cmd);
    EXPECT_EQ(r.exitCode, 2) << cmd;
    EXPECT_EQ(countLines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("no_such_dataset"), std::string::npos) << r.err;
  }
}

}  // namespace
}  // namespace vegstream::testing
