// Importing the Zion sample (EPSG:4326 SRTM + three UTM 12N Landsat bands) through the real
// executable, then checking the tiles against the sources.

#include <gtest/gtest.h>

#include <random>

#include "datasets/raster_source.h"
#include "geo/crs.h"
#include "geo/projection.h"
#include "import_test_util.h"

namespace vegstream::datasets {
namespace {
using namespace vegstream::datasets::test;

// The import, made once per build for all test processes (cachedFixture): a test
// whose import failed fails with the command's message.
class ZionImport : public ::testing::Test {
 protected:
  void SetUp() override {
    auto dir =
        testing::cachedFixture("import-zion-z14-cubic", testing::vegstreamKey(), [](const fs::path& out) -> Status {
          const std::string z = samples() + "/zion/";
          // --max-zoom 14 (7.6 m pixels, 4× finer than the automatic zoom 12) and cubic height
          // resampling: the height check samples the tiles bilinearly at the DEM's pixel centres, and
          // a bilinear import's kinks leave 19 % of them beyond 0.5 m even at zoom 14 (README,
          // "Height accuracy").
          const auto r = testing::runVegstream(
              "import --dem " + z + "srtm.tif --imagery-bands " + z + "landsat_b4.tif," + z + "landsat_b3.tif," + z +
              "landsat_b2.tif --stretch p1,p99 --max-zoom 14 --height-resampling cubic --out " + out.string());
          if (r.exitCode != 0)
            return makeError(ErrorKind::Internal,
                             "vegstream import: exit " + std::to_string(r.exitCode) + ": " + r.err);
          return {};
        });
    ASSERT_TRUE(dir.ok()) << dir.error().message;
    out_ = *dir;
  }
  fs::path out_;
};

TEST_F(ZionImport, SucceedsAndRecordsTheDataset) {
  auto meta = readDatasetMeta(out_);
  ASSERT_TRUE(meta) << meta.error().message;
  EXPECT_EQ(meta->maxZoom, 14);
  EXPECT_LE(meta->minZoom, 9);
  EXPECT_NEAR(meta->maxHeightM, 2892.0, 1.0);
  EXPECT_NEAR(meta->minHeightM, 1024.0, 5.0);
  EXPECT_NEAR(meta->bounds.westDeg, -113.2396, 1e-3);
  EXPECT_NEAR(meta->bounds.northDeg, 37.5129, 1e-3);
  EXPECT_GT(meta->elevationTiles, 200u);
  EXPECT_EQ(meta->imagery, ImageryFormat::Jpeg);
  ASSERT_EQ(meta->sources.size(), 2u);
  EXPECT_NE(meta->sources[1].crs.find("32612"), std::string::npos);
}

TEST_F(ZionImport, HeightsMatchTheDemAtItsPixelCentres) {
  auto meta = readDatasetMeta(out_);
  ASSERT_TRUE(meta);
  auto dem = readWholeRaster(samples() + "/zion/srtm.tif");
  ASSERT_TRUE(dem);
  DatasetSampler sampler(out_, *meta);
  std::mt19937 rng(2024);
  std::uniform_int_distribution<int> col(0, dem->width - 1), row(0, dem->height - 1);
  const double tolerance = 0.5 + encodingStepM(meta->elevationEncoding);
  int checked = 0, within = 0;
  while (checked < 1000) {
    const int i = col(rng), j = row(rng);
    const float src = dem->at(i, j);
    if (dem->isNodata(src)) continue;
    const auto c = dem->georef.pixelCentre(i, j);  // lon, lat
    const double h = sampler.height(c[0], c[1]);
    ++checked;
    within += std::abs(h - src) <= tolerance;
  }
  EXPECT_GE(within, 990) << "of 1000 DEM pixel centres within " << tolerance << " m";
}

// Landsat pixels in flat, homogeneous places (3×3 neighbourhood spread below 2 % of the
// stretch range), checked against the stretched source colour. Tolerance 12 of 255: JPEG at
// quality 90 with 4:2:0 chroma subsampling moves a smooth colour by a few levels, bilinear
// resampling of a homogeneous block by less than the neighbourhood spread (≈ 5 levels).
TEST_F(ZionImport, ColourMatchesTheStretchedLandsat) {
  auto meta = readDatasetMeta(out_);
  ASSERT_TRUE(meta);
  const std::string z = samples() + "/zion/";
  auto r = readWholeRaster(z + "landsat_b4.tif"), g = readWholeRaster(z + "landsat_b3.tif"),
       b = readWholeRaster(z + "landsat_b2.tif");
  ASSERT_TRUE(r && g && b);
  // Stretch ranges as dataset.json records them (the importer's p1/p99 of each band).
  const Raster* bands[3] = {&*r, &*g, &*b};
  double lo[3], hi[3];
  const std::string& d = meta->sources[1].description;
  for (int k = 0; k < 3; ++k) {
    const std::string key = std::string(1, "RGB"[k]) + " ";
    const auto at = d.find(key, d.find("stretched"));
    ASSERT_NE(at, std::string::npos) << d;
    ASSERT_EQ(std::sscanf(d.c_str() + at + 2, "%lf…%lf", &lo[k], &hi[k]), 2) << d;
  }
  EXPECT_NEAR(lo[0], 6700, 500);  // README: 1st–99th percentiles roughly 6700 … 18300
  EXPECT_NEAR(hi[0], 18300, 500);

  auto crs = Result<geo::Crs>(geo::utmCrs(12, true));
  ASSERT_TRUE(crs);
  DatasetSampler sampler(out_, *meta);
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> col(5, r->width - 6), row(5, r->height - 6);
  int checked = 0, good = 0;
  for (int attempt = 0; attempt < 200000 && checked < 20; ++attempt) {
    const int i = col(rng), j = row(rng);
    bool flat = true;
    double centre[3];
    for (int k = 0; k < 3 && flat; ++k) {
      double mn = 1e9, mx = -1e9;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const double v = bands[k]->at(i + dx, j + dy);
          mn = std::min(mn, v);
          mx = std::max(mx, v);
        }
      flat = mx - mn < 0.02 * (hi[k] - lo[k]) && mx < 65535;
      centre[k] = std::clamp((bands[k]->at(i, j) - lo[k]) * 255.0 / (hi[k] - lo[k]), 0.0, 255.0);
    }
    if (!flat) continue;
    const auto xy = r->georef.pixelCentre(i, j);
    const geo::Geodetic p = geo::fromProjected(*crs, {xy[0], xy[1]});
    const auto c = sampler.colour(p.lonDeg, p.latDeg);
    if (!c) continue;
    ++checked;
    int worst = 0;
    for (int k = 0; k < 3; ++k)
      worst = std::max(worst, std::abs((*c)[static_cast<size_t>(k)] - int(std::lround(centre[k]))));
    good += worst <= 12;
    EXPECT_LE(worst, 12) << "Landsat pixel " << i << "," << j;
  }
  EXPECT_EQ(checked, 20);
  EXPECT_EQ(good, checked);
}

}  // namespace
}  // namespace vegstream::datasets
