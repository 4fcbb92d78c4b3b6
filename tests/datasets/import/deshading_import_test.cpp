// De-shading through the real `vegstream import`: a synthetic ring-shaped ridge (every aspect,
// slopes up to 34°) and a uniform albedo photographed under a known sun (8-bit sRGB GeoTIFFs
// written here). De-shaded with that sun — stated, or from a datetime — the imagery comes out
// flat; estimated from the imagery, the sun comes out within a few degrees; a flat DEM gives
// no estimate and dataset.json says so.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>

#include "datasets/deshading.h"
#include "datasets/srgb.h"
#include "geo/datetime.h"
#include "geo/solar_position.h"
#include "import_test_util.h"
#include "tests/datasets/tiny_tiff.h"

namespace vegstream::datasets {
namespace {
using namespace vegstream::datasets::test;
using vegstream::testing::runVegstream;

constexpr double kLat0 = 37.024, kLon0 = -113.024;  // north-west corner
constexpr double kDemPx = 0.0002, kImgPx = 0.0001;  // degrees (≈ 22 m and 11 m)
constexpr int kDemN = 240, kImgN = 480;             // both span 0.048°
constexpr double kLatC = kLat0 - 0.024, kLonC = kLon0 + 0.024;
constexpr double kEarthR = 6371000.0, kRingR = 1500.0, kRingW = 500.0, kRingA = 400.0;
const glm::dvec3 kAlbedo(0.20, 0.16, 0.09);  // linear

// Metres east and north of the centre.
glm::dvec2 metres(double lon, double lat) {
  const double d = M_PI / 180.0 * kEarthR;
  return {(lon - kLonC) * d * std::cos(kLatC * M_PI / 180.0), (lat - kLatC) * d};
}

double ringHeight(glm::dvec2 p, bool flat) {
  if (flat) return 1000.0;
  const double u = (glm::length(p) - kRingR) / kRingW;
  return 1000.0 + kRingA * std::exp(-u * u);
}

glm::dvec3 ringNormal(glm::dvec2 p) {
  const double d = std::max(glm::length(p), 1e-6), u = (d - kRingR) / kRingW;
  const double dhdd = kRingA * std::exp(-u * u) * (-2.0 * u / kRingW);
  return glm::normalize(glm::dvec3(-dhdd * p.x / d, -dhdd * p.y / d, 1.0));
}

const std::vector<uint16_t> kWgs84Keys = {1, 1, 0, 3, 1024, 0, 1, 2, 1025, 0, 1, 1, 2048, 0, 1, 4326};

void writeGeoTiff(const fs::path& path, uint32_t n, double px, uint16_t channels, uint16_t bits, uint16_t format,
                  std::vector<uint8_t> pixels) {
  TinyImage img;
  img.width = img.height = n;
  img.channels = channels;
  img.bits = bits;
  img.sampleFormat = format;
  img.pixels = std::move(pixels);
  img.extra = {doubles(33550, {px, px, 0}), doubles(33922, {0, 0, 0, kLon0, kLat0, 0}), shorts(34735, kWgs84Keys)};
  writeTinyTiff(path, img);
}

// dem.tif (Float32) and img.tif (8-bit sRGB RGB of kAlbedo lit by `sun`) in `dir`.
void writeScene(const fs::path& dir, const SunAngles& sun, bool flat = false) {
  std::vector<float> h;
  for (int j = 0; j < kDemN; ++j)
    for (int i = 0; i < kDemN; ++i)
      h.push_back(static_cast<float>(ringHeight(metres(kLon0 + (i + 0.5) * kDemPx, kLat0 - (j + 0.5) * kDemPx), flat)));
  writeGeoTiff(dir / "dem.tif", kDemN, kDemPx, 1, 32, 3, pixelBytes(h));
  const glm::dvec3 s = sunVectorEnu(sun);
  const double flatShading = shading({0, 0, 1}, s, kDirectFraction);
  std::vector<uint8_t> rgb;
  for (int j = 0; j < kImgN; ++j)
    for (int i = 0; i < kImgN; ++i) {
      const glm::dvec2 p = metres(kLon0 + (i + 0.5) * kImgPx, kLat0 - (j + 0.5) * kImgPx);
      const glm::dvec3 n = flat ? glm::dvec3(0, 0, 1) : ringNormal(p);
      const double lit = shading(n, s, kDirectFraction) / flatShading;
      for (int c = 0; c < 3; ++c) rgb.push_back(srgbEncode8(static_cast<float>(kAlbedo[c] * lit)));
    }
  writeGeoTiff(dir / "img.tif", kImgN, kImgPx, 3, 8, 1, rgb);
}

struct Spread {
  double meanLuminance = 0.0, cv = 0.0;  // linear luminance over the ring, and its std / mean
  int pixels = 0;
};

// Linear luminance of the max-zoom imagery pixels within 2.4 km of the centre (the ring and its
// flanks, away from the data's edge).
Spread ringSpread(const fs::path& dataset) {
  auto meta = readDatasetMeta(dataset);
  EXPECT_TRUE(meta) << meta.error().message;
  Spread s;
  if (!meta) return s;
  double sum = 0.0, sq = 0.0;
  for (const auto& id : geo::tilesCovering(meta->bounds, meta->maxZoom)) {
    auto tile = readColorTile(imageryTilePath(dataset, id, *meta->imagery), id, kTileSize);
    if (!tile) continue;
    for (int j = 0; j < tile->size; ++j)
      for (int i = 0; i < tile->size; ++i) {
        const glm::dvec2 ll = geo::pixelToLonLat(id, {i + 0.5, j + 0.5}, tile->size);
        if (glm::length(metres(ll.x, ll.y)) > 2400.0) continue;
        const uint8_t* p =
            &tile->rgba[(static_cast<size_t>(j) * static_cast<size_t>(tile->size) + static_cast<size_t>(i)) * 4];
        if (p[3] == 0) continue;
        const double y = 0.2126 * srgbDecode(p[0] / 255.0f) + 0.7152 * srgbDecode(p[1] / 255.0f) +
                         0.0722 * srgbDecode(p[2] / 255.0f);
        sum += y;
        sq += y * y;
        ++s.pixels;
      }
  }
  if (s.pixels == 0) return s;
  s.meanLuminance = sum / s.pixels;
  s.cv = std::sqrt(std::max(0.0, sq / s.pixels - s.meanLuminance * s.meanLuminance)) / s.meanLuminance;
  return s;
}

const double kAlbedoLuminance = 0.2126 * kAlbedo.r + 0.7152 * kAlbedo.g + 0.0722 * kAlbedo.b;

fs::path importScene(const fs::path& dir, const std::string& outName, const std::string& extra) {
  const fs::path out = dir / outName;
  const auto r = runVegstream("import --dem " + (dir / "dem.tif").string() + " --imagery " +
                              (dir / "img.tif").string() + " --imagery-format png " + extra + " --out " + out.string());
  EXPECT_EQ(r.exitCode, 0) << r.err;
  return out;
}

DeshadingRecord deshadingOf(const fs::path& dataset) {
  auto meta = readDatasetMeta(dataset);
  EXPECT_TRUE(meta) << meta.error().message;
  if (!meta || !meta->radiometry || !meta->radiometry->deshading) {
    ADD_FAILURE() << dataset << " records no imagery.radiometry.deshading";
    return {};
  }
  EXPECT_EQ(meta->radiometry->method, "srgb");
  return *meta->radiometry->deshading;
}

// Without de-shading the ring's flanks differ by their shading (the luminance spread is that of
// the shading, about 20 %); with the stated sun they come out as the one albedo they are.
TEST(DeshadingImport, TheStatedSunTakesTheRidgesShadingOut) {
  const SunAngles sun{135.0, 50.0};
  const fs::path dir = importTmp("given");
  writeScene(dir, sun);
  const Spread shaded = ringSpread(importScene(dir, "off", "--deshading off"));
  const fs::path out = importScene(dir, "given", "--imagery-sun 135,50");
  const Spread flat = ringSpread(out);
  ASSERT_GT(shaded.pixels, 10000);
  std::printf("ring luminance spread (std/mean): %.4f shaded, %.4f de-shaded; mean %.4f (albedo %.4f)\n", shaded.cv,
              flat.cv, flat.meanLuminance, kAlbedoLuminance);
  EXPECT_GT(shaded.cv, 0.12);
  EXPECT_LT(flat.cv, 0.03) << "against " << shaded.cv << " shaded";
  EXPECT_NEAR(flat.meanLuminance, kAlbedoLuminance, 0.02 * kAlbedoLuminance);
  const DeshadingRecord d = deshadingOf(out);
  EXPECT_EQ(d.source, "given");
  EXPECT_DOUBLE_EQ(d.sunAzimuthDeg, 135.0);
  EXPECT_DOUBLE_EQ(d.sunElevationDeg, 50.0);
  EXPECT_DOUBLE_EQ(d.directFraction, kDirectFraction);
  EXPECT_EQ(deshadingOf(dir / "off").source, "none");
}

// The sun of --imagery-datetime at the dataset's centre (NOAA's equations, geo/solar_position.h).
TEST(DeshadingImport, TheImageryDatetimesSunTakesTheShadingOut) {
  const std::string when = "2015-08-18T17:58:00Z";
  const auto t = geo::parseIsoDateTime(when);
  ASSERT_TRUE(t);
  const geo::SolarPosition p = geo::solarPosition(t->unixMs, kLatC, kLonC);
  const fs::path dir = importTmp("datetime");
  writeScene(dir, {p.azimuthDeg, p.elevationDeg});
  const fs::path out = importScene(dir, "out", "--imagery-datetime " + when);
  EXPECT_LT(ringSpread(out).cv, 0.03);
  auto meta = readDatasetMeta(out);
  ASSERT_TRUE(meta);
  EXPECT_EQ(meta->imageryDatetime, when);
  const DeshadingRecord d = deshadingOf(out);
  EXPECT_EQ(d.source, "imagery datetime");
  EXPECT_NEAR(d.sunAzimuthDeg, p.azimuthDeg, 1e-6);
  EXPECT_NEAR(d.sunElevationDeg, p.elevationDeg, 1e-6);
}

TEST(DeshadingImport, WithoutATimeTheSunIsEstimatedFromTheImagery) {
  const SunAngles sun{230.0, 40.0};
  const fs::path dir = importTmp("estimated");
  writeScene(dir, sun);
  const fs::path out = importScene(dir, "out", "");
  const DeshadingRecord d = deshadingOf(out);
  EXPECT_EQ(d.source, "estimated") << d.note;
  std::printf("estimated sun: azimuth %.2f, elevation %.2f (true 230, 40): %s\n", d.sunAzimuthDeg, d.sunElevationDeg,
              d.note.c_str());
  EXPECT_LT(std::abs(std::remainder(d.sunAzimuthDeg - sun.azimuthDeg, 360.0)), 3.0) << d.sunAzimuthDeg;
  EXPECT_LT(std::abs(d.sunElevationDeg - sun.elevationDeg), 4.0) << d.sunElevationDeg;
  EXPECT_LT(ringSpread(out).cv, 0.04);
}

TEST(DeshadingImport, FlatTerrainGivesNoEstimateAndSaysSo) {
  const fs::path dir = importTmp("flat");
  writeScene(dir, {135.0, 50.0}, true);
  const DeshadingRecord d = deshadingOf(importScene(dir, "out", ""));
  EXPECT_EQ(d.source, "none");
  EXPECT_NE(d.note.find("too flat"), std::string::npos) << d.note;
}

}  // namespace
}  // namespace vegstream::datasets
