// `vegstream import --imagery-nir` on the Zion sample (Landsat band 5 with bands 4, 3, 2), and
// `vegstream query`'s NDVI checked against GDAL's own NDVI of the band files (gdal_calc.py,
// installed by scripts/setup), read with readGeoTiff and sampled bilinearly at each point's
// UTM coordinate — an independent reference for the import's reprojection, NDVI and encoding.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <nlohmann/json.hpp>

#include "datasets/dataset_reader.h"
#include "datasets/raster_source.h"
#include "geo/crs.h"
#include "geo/projection.h"
#include "import_test_util.h"
#include "scene/dataset_calibration.h"
#include "vegetation/colour_score.h"
#include "vegetation/species_choice.h"

namespace vegstream::datasets {
namespace {
using namespace vegstream::datasets::test;
using nlohmann::json;
using vegstream::testing::runCommand;
using vegstream::testing::runVegstream;

const std::string kZion = samples() + "/zion/";

// Zoom 13 (15 m tiles over 30 m Landsat pixels): ~140 max-zoom tiles, a few seconds on two
// cores, and fine enough that the tiles' own bilinear step adds little to the comparison.
class ZionNirImport : public ::testing::Test {
 protected:
  void SetUp() override {
    auto dir = testing::cachedFixture("import-zion-nir-z13", testing::vegstreamKey(), [](const fs::path& out) -> Status {
      const auto r = runVegstream("import --dem " + kZion + "srtm.tif --imagery-bands " + kZion + "landsat_b4.tif," +
                                  kZion + "landsat_b3.tif," + kZion + "landsat_b2.tif --imagery-nir " + kZion +
                                  "landsat_b5.tif --stretch p1,p99 --max-zoom 13 --out " + out.string());
      if (r.exitCode != 0)
        return makeError(ErrorKind::Internal, "vegstream import: exit " + std::to_string(r.exitCode) + ": " + r.err);
      return {};
    });
    ASSERT_TRUE(dir.ok()) << dir.error().message;
    out_ = *dir;
  }
  fs::path out_;
};

// Bilinear between pixel centres of a one-band north-up raster at CRS (x, y); NaN where any of
// the four samples is nodata or outside.
double bilinearAt(const Raster& r, double x, double y) {
  const auto& t = r.georef.transform;
  const double c = (x - t[0]) / t[1] - 0.5, w = (y - t[3]) / t[5] - 0.5;
  const int c0 = static_cast<int>(std::floor(c)), r0 = static_cast<int>(std::floor(w));
  if (c0 < 0 || r0 < 0 || c0 + 1 >= r.width || r0 + 1 >= r.height) return NAN;
  const double fx = c - c0, fy = w - r0;
  const double v00 = r.at(c0, r0), v10 = r.at(c0 + 1, r0), v01 = r.at(c0, r0 + 1), v11 = r.at(c0 + 1, r0 + 1);
  for (double v : {v00, v10, v01, v11})
    if (r.isNodata(static_cast<float>(v))) return NAN;
  return (v00 * (1 - fx) + v10 * fx) * (1 - fy) + (v01 * (1 - fx) + v11 * fx) * fy;
}

TEST_F(ZionNirImport, RecordsTheNdviLayer) {
  auto meta = readDatasetMeta(out_);
  ASSERT_TRUE(meta) << meta.error().message;
  EXPECT_TRUE(meta->ndvi);
  EXPECT_EQ(meta->maxZoom, 13);
  ASSERT_EQ(meta->sources.size(), 3u);
  EXPECT_EQ(meta->sources[2].role, "nir");
  EXPECT_NE(meta->sources[2].path.find("landsat_b5.tif"), std::string::npos);
  EXPECT_NE(meta->sources[2].crs.find("32612"), std::string::npos);
  EXPECT_NE(meta->sources[2].description.find("same grid"), std::string::npos) << meta->sources[2].description;
  // NDVI wherever there is imagery: the layers cover the same tiles.
  EXPECT_GT(meta->ndviTiles, 100u);
  EXPECT_EQ(meta->ndviTiles, meta->imageryTiles);

  const auto r = runVegstream("info " + out_.string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["tiles"]["ndvi"].get<uint64_t>(), meta->ndviTiles);
  EXPECT_EQ(j["tiles"]["on_disk"]["ndvi"].get<uint64_t>(), meta->ndviTiles);
  EXPECT_EQ(j["bytes"], j["bytes_on_disk"]);  // the NDVI tiles' bytes are counted
}

// GDAL's NDVI of the Zion bands (Float32, nodata −9999) in `dir`, read back with readGeoTiff. A
// missing GDAL is a broken setup, not a skip.
Result<Raster> gdalNdvi(const fs::path& dir) {
  if (runCommand("command -v gdal_calc.py").exitCode != 0)
    return makeError(ErrorKind::NotFound, "gdal_calc.py (GDAL's Python tools) is not installed: run scripts/setup");
  const fs::path ref = dir / "ndvi.tif";
  const auto calc = runCommand("gdal_calc.py --quiet -A " + kZion + "landsat_b5.tif -B " + kZion +
                               "landsat_b4.tif --calc='(A.astype(float)-B)/(A.astype(float)+B)' --type=Float32 "
                               "--NoDataValue=-9999 --outfile=" + ref.string());
  if (calc.exitCode != 0) return makeError(ErrorKind::Internal, "gdal_calc.py failed: " + calc.err + calc.out);
  return readWholeRaster(ref.string());
}

// An 11 × 11 grid of points over `b`, 3 % in from its edges, printed to 7 decimals as the
// command line gets them ("37.1435084"), with GDAL's NDVI there (bilinear at the UTM position);
// points where GDAL has none are left out.
struct Point {
  std::string lat, lon;
  double gdal = 0.0;
};
std::vector<Point> gridPoints(const geo::GeoBounds& b, const Raster& gdal) {
  auto utm = Result<geo::Crs>(geo::utmCrs(12, true));
  std::vector<Point> out;
  for (int gy = 0; gy < 11; ++gy)
    for (int gx = 0; gx < 11; ++gx) {
      char lat[32], lon[32];
      std::snprintf(lat, sizeof lat, "%.7f", b.southDeg + (b.northDeg - b.southDeg) * (0.03 + 0.94 * gy / 10.0));
      std::snprintf(lon, sizeof lon, "%.7f", b.westDeg + (b.eastDeg - b.westDeg) * (0.03 + 0.94 * gx / 10.0));
      auto xy = geo::toProjected(*utm, {std::stod(lat), std::stod(lon), 0.0});
      const double v = xy ? bilinearAt(gdal, xy->x, xy->y) : NAN;
      if (!std::isnan(v)) out.push_back({lat, lon, v});
    }
  return out;
}

struct Agreement {
  double median = 0.0, p95 = 0.0, max = 0.0;
};
Agreement agreement(std::vector<double> diffs, const char* what) {
  std::sort(diffs.begin(), diffs.end());
  Agreement a;
  if (diffs.empty()) return a;
  a.median = diffs[diffs.size() / 2];
  a.p95 = diffs[static_cast<size_t>(0.95 * static_cast<double>(diffs.size() - 1))];
  a.max = diffs.back();
  std::printf("%s: NDVI vs GDAL at %zu points: median |diff| %.4f, p95 %.4f, max %.4f\n", what, diffs.size(), a.median,
              a.p95, a.max);
  return a;
}

TEST_F(ZionNirImport, QueryNdviMatchesGdal) {
  auto gdal = gdalNdvi(testing::testOutputDir());
  ASSERT_TRUE(gdal) << gdal.error().message;
  ASSERT_EQ(gdal->georef.crs->epsg().value_or(0), 32612);
  auto meta = readDatasetMeta(out_);
  ASSERT_TRUE(meta);
  const std::vector<Point> points = gridPoints(meta->bounds, *gdal);
  ASSERT_GE(points.size(), 100u);
  // The catalog as query sees it: with the dataset's colour calibration (issue 41 item 1).
  const vegetation::SpeciesCatalog catalog = scene::calibratedCatalog(vegetation::defaultSpeciesCatalog(), *meta);
  std::vector<double> diffs;
  for (const Point& p : points) {  // each query is a process start, ~0.25 s
    const auto r = runVegstream("query " + out_.string() + " --lat " + p.lat + " --lon " + p.lon);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const json j = json::parse(r.out);
    if (!j["ndvi"].is_number()) {
      ADD_FAILURE() << "no NDVI at lat " << p.lat << ", lon " << p.lon << " where GDAL has " << p.gdal;
      continue;
    }
    diffs.push_back(std::abs(j["ndvi"].get<double>() - p.gdal));
    // The species query prints are chosen with the NDVI, through the calibration
    // (vegetation::speciesCandidatesAt).
    const auto& c = j["color"];
    const auto lin = [&](const char* k) { return vegetation::srgbDecode(c[k].get<uint8_t>() / 255.0f); };
    const auto k = vegetation::speciesCandidatesAt(catalog, glm::vec3(lin("r"), lin("g"), lin("b")),
                                                   j["ndvi"].get<float>());
    if (k.first < 0) {
      EXPECT_TRUE(j["species"].is_null()) << r.out;
    } else {
      EXPECT_EQ(j["species"], catalog.species[static_cast<size_t>(k.first)].name) << r.out;
      // The printed NDVI is rounded to 4 decimals; the score moves little with that.
      EXPECT_NEAR(j["species_candidates"][0]["probability"].get<double>(), 1.0 - k.secondRatio, 2e-3) << r.out;
    }
  }
  const Agreement a = agreement(diffs, "same grid, zoom 13");
  // Measured (121 points): median 0.0014, p95 0.005, max 0.012. The encoding's step is 1/127
  // (±0.004), and the NDVI is resampled twice (imagery grid → 15 m tiles → the point) where
  // GDAL's is sampled once; the bounds leave about twice the measured room.
  EXPECT_LE(a.median, 0.005);
  EXPECT_LE(a.p95, 0.01);
  EXPECT_LE(a.max, 0.03);
}

// The NIR in another CRS and on another grid than the imagery (band 5 warped by GDAL to
// geographic coordinates): the importer reprojects it onto the imagery's pixels.
TEST(ZionNirReprojected, NdviMatchesGdal) {
  const fs::path dir = testing::testOutputDir();
  auto gdal = gdalNdvi(dir);
  ASSERT_TRUE(gdal) << gdal.error().message;
  const fs::path warped = dir / "b5_wgs84.tif";
  const auto warp = runCommand("gdalwarp -q -t_srs EPSG:4326 -r bilinear " + kZion + "landsat_b5.tif " +
                               warped.string());
  ASSERT_EQ(warp.exitCode, 0) << warp.err;
  const fs::path out = dir / "zion";
  const auto r = runVegstream("import --dem " + kZion + "srtm.tif --imagery-bands " + kZion + "landsat_b4.tif," +
                              kZion + "landsat_b3.tif," + kZion + "landsat_b2.tif --imagery-nir " + warped.string() +
                              " --stretch p1,p99 --max-zoom 12 --out " + out.string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  auto reader = DatasetReader::open(out);
  ASSERT_TRUE(reader) << reader.error().message;
  EXPECT_NE(reader->meta().sources[2].crs.find("4326"), std::string::npos);
  EXPECT_NE(reader->meta().sources[2].description.find("reprojected"), std::string::npos);
  const std::vector<Point> points = gridPoints(reader->meta().bounds, *gdal);
  ASSERT_GE(points.size(), 100u);
  std::vector<double> diffs;
  for (const Point& p : points) {
    auto v = reader->ndviAt(std::stod(p.lat), std::stod(p.lon));
    ASSERT_TRUE(v) << v.error().message;
    ASSERT_TRUE(v->has_value()) << "no NDVI at lat " << p.lat << ", lon " << p.lon;
    diffs.push_back(std::abs(**v - p.gdal));
  }
  const Agreement a = agreement(diffs, "NIR warped to EPSG:4326, zoom 12");
  // Measured (121 points): median 0.0044, p95 0.016, max 0.041: GDAL's own warp (bilinear, onto
  // a rotated grid) smooths the NIR before the import resamples it again.
  EXPECT_LE(a.median, 0.01);
  EXPECT_LE(a.p95, 0.03);
}

}  // namespace
}  // namespace vegstream::datasets
