// RasterSource (GDAL) on the real sample files in ../shared/datasets (see its README for the figures).

#include "datasets/raster_source.h"

#include <algorithm>
#include <filesystem>
#include <limits>

#include <gtest/gtest.h>

namespace vegstream::datasets {
namespace {
namespace fs = std::filesystem;

fs::path sample(const char* rel) { return fs::path(VEGSTREAM_DATASETS_DIR) / rel; }

struct MinMax {
  float min = std::numeric_limits<float>::max();
  float max = std::numeric_limits<float>::lowest();
  size_t nodata = 0;
};

MinMax minMax(const Raster& r, int channel = 0) {
  MinMax m;
  for (int row = 0; row < r.height; ++row)
    for (int col = 0; col < r.width; ++col) {
      const float v = r.at(col, row, channel);
      if (r.isNodata(v)) {
        ++m.nodata;
        continue;
      }
      m.min = std::min(m.min, v);
      m.max = std::max(m.max, v);
    }
  return m;
}

TEST(GeoTiffSamples, ZionSrtmHeightsAndGrid) {
  auto r = readWholeRaster(fs::path(sample("zion/srtm.tif")).string());
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(r->width, 465);
  EXPECT_EQ(r->height, 457);
  EXPECT_EQ(r->channels, 1);
  EXPECT_EQ(r->georef.crs->epsg().value_or(0), 4326);
  EXPECT_NE(r->georef.crsDescription.find("WGS 84"), std::string::npos);
  // Its nodata (65535) is GDAL's mask, read as NaN.
  EXPECT_FALSE(r->nodata.has_value());
  // Raw digital numbers (metres), not OIIO's 0..1 normalisation of UInt16.
  const MinMax m = minMax(*r);
  EXPECT_EQ(m.min, 1024.0f);
  EXPECT_EQ(m.max, 2892.0f);
  const double px = 0.000833333333;
  EXPECT_NEAR(r->georef.transform[1], px, 1e-9);
  EXPECT_NEAR(r->georef.transform[5], -px, 1e-9);
  const auto c = r->georef.pixelCentre(0, 0);
  EXPECT_NEAR(c[0], -113.2396 + px / 2, 1e-4);
  EXPECT_NEAR(c[1], 37.5129 - px / 2, 1e-4);
  // The far corner closes the README's extent (lon −112.8521, lat 37.1321).
  const auto far = r->georef.pixelCentre(464.5, 456.5);
  EXPECT_NEAR(far[0], -112.8521, 1e-4);
  EXPECT_NEAR(far[1], 37.1321, 1e-4);
}

TEST(GeoTiffSamples, ZionLandsatIsUtm12WithRawDigitalNumbers) {
  auto r = readWholeRaster(fs::path(sample("zion/landsat_b4.tif")).string());
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(r->width, 1128);
  EXPECT_EQ(r->height, 1428);
  EXPECT_EQ(r->georef.crs->epsg().value_or(0), 32612);
  EXPECT_NE(r->georef.crsDescription.find("UTM zone 12N"), std::string::npos);
  const auto& t = r->georef.transform;
  EXPECT_DOUBLE_EQ(t[0], 301905.0);
  EXPECT_DOUBLE_EQ(t[3], 4154085.0);
  EXPECT_DOUBLE_EQ(t[1], 30.0);
  EXPECT_DOUBLE_EQ(t[5], -30.0);
  EXPECT_EQ(t[2], 0.0);
  EXPECT_EQ(t[4], 0.0);
  // 1st and 99th percentiles, roughly 6700 … 18300 per the README.
  std::vector<float> v;
  for (float s : r->samples)
    if (!r->isNodata(s)) v.push_back(s);
  ASSERT_GT(v.size(), v.size() / 2);
  std::sort(v.begin(), v.end());
  EXPECT_NEAR(v[v.size() / 100], 6700.0f, 700.0f);
  EXPECT_NEAR(v[v.size() * 99 / 100], 18300.0f, 1500.0f);
}

TEST(GeoTiffSamples, GoletaCorruptKeysNeedTheUserCrs) {
  auto r = readWholeRaster(fs::path(sample("goleta/sba_elev32_wgs84_512x512.tif")).string());
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().kind, ErrorKind::Unsupported);
  const std::string& msg = r.error().message;
  EXPECT_NE(msg.find("sba_elev32_wgs84_512x512.tif"), std::string::npos) << msg;
  EXPECT_NE(msg.find("names no CRS"), std::string::npos) << msg;  // GDAL ignores its corrupt GeoKeys
  EXPECT_NE(msg.find("--dem-crs"), std::string::npos) << msg;
}

TEST(GeoTiffSamples, GoletaRecoversWithAssumedEpsg) {
  SourceOptions opt;
  opt.assumeCrs = *geo::Crs::fromUserInput("EPSG:4326");
  auto r = readWholeRaster(fs::path(sample("goleta/sba_elev32_wgs84_512x512.tif")).string(), opt);
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(r->width, 512);
  EXPECT_EQ(r->height, 512);
  EXPECT_EQ(r->georef.crs->epsg().value_or(0), 4326);
  const MinMax m = minMax(*r);  // its nodata (-9999) is NaN
  EXPECT_NEAR(m.min, 2.5f, 0.05f);
  EXPECT_NEAR(m.max, 20.7f, 0.05f);
  EXPECT_NEAR(r->georef.transform[0], -119.8337, 1e-9);
  EXPECT_NEAR(r->georef.transform[3], 34.4448, 1e-9);
  EXPECT_NEAR(r->georef.transform[1], 3.02734375e-5, 1e-12);
  EXPECT_NEAR(r->georef.transform[5], -3.02734375e-5, 1e-12);
}

TEST(GeoTiffSamples, GoletaRgbHasSoundKeys) {
  auto r = readWholeRaster(fs::path(sample("goleta/sba_rgb_wgs84_512x512.tif")).string());
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(r->channels, 3);
  EXPECT_EQ(r->georef.crs->epsg().value_or(0), 4326);
  EXPECT_FALSE(r->nodata.has_value());
  const MinMax m = minMax(*r, 1);
  EXPECT_GE(m.min, 0.0f);
  EXPECT_LE(m.max, 255.0f);
  EXPECT_GT(m.max, 100.0f);  // 0..255, not normalised to 0..1
}

TEST(GeoTiffSamples, AssumedEpsgOverridesTheFile) {
  SourceOptions opt;
  opt.assumeCrs = *geo::Crs::fromUserInput("EPSG:4269");
  auto r = readWholeRaster(fs::path(sample("zion/srtm.tif")).string(), opt);
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(r->georef.crs->epsg().value_or(0), 4269);
}

TEST(GeoTiffSamples, NodataOverrideWins) {
  SourceOptions opt;
  opt.nodataOverride = 1024.0;
  auto r = readWholeRaster(fs::path(sample("zion/srtm.tif")).string(), opt);
  ASSERT_TRUE(r.ok()) << r.error().message;
  const MinMax m = minMax(*r);
  EXPECT_GT(m.min, 1024.0f);  // 1024 is now no data (NaN)
  EXPECT_GT(m.nodata, 0u);
}

TEST(GeoTiffSamples, RmnpDemHasNonSquarePixels) {
  auto r = readWholeRaster(fs::path(sample("rmnp/rmnp-dem.tif")).string());
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(r->width, 152);
  EXPECT_EQ(r->height, 187);
  EXPECT_EQ(r->georef.crs->epsg().value_or(0), 4326);
  EXPECT_NEAR(r->georef.transform[1], 0.00275, 1e-12);
  EXPECT_NEAR(r->georef.transform[5], -0.00211, 1e-12);
  const MinMax m = minMax(*r);
  EXPECT_EQ(m.min, 2281.0f);
  EXPECT_EQ(m.max, 4261.0f);
}

TEST(GeoTiffSamples, RmnpRgbHasThreeChannels) {
  auto r = readWholeRaster(fs::path(sample("rmnp/rmnp-rgb.tif")).string());
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(r->width, 485);
  EXPECT_EQ(r->height, 373);
  EXPECT_EQ(r->channels, 3);
  EXPECT_EQ(r->georef.crs->epsg().value_or(0), 4326);
  EXPECT_NEAR(r->georef.transform[1], 0.0015, 1e-12);
  EXPECT_NEAR(r->georef.transform[5], -0.0015, 1e-12);
  // Nodata 255 per band: NaN where GDAL's mask says so.
  EXPECT_GT(minMax(*r).nodata, 0u);
}

}  // namespace
}  // namespace vegstream::datasets
