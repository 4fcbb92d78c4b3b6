// The radiometry of imported imagery (datasets/radiometry.h): the method auto picks, Landsat
// names, dark-object subtraction; and the de-shading maths (deshading.h, sun_estimate.h) on
// synthetic terrain whose shading is known.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>
#include <sstream>

#include <glm/geometric.hpp>

#include "datasets/dataset_format.h"
#include "datasets/deshading.h"
#include "datasets/radiometry.h"
#include "datasets/srgb.h"
#include "datasets/sun_estimate.h"
#include "tests/support/test_dirs.h"

namespace vegstream::datasets {
namespace {
namespace fs = std::filesystem;

TEST(Radiometry, ParsesTheFourMethodsAndNamesTheOptionOtherwise) {
  EXPECT_EQ(*parseRadiometryMethod("auto"), RadiometryMethod::Auto);
  EXPECT_EQ(*parseRadiometryMethod("reflectance"), RadiometryMethod::Reflectance);
  EXPECT_EQ(*parseRadiometryMethod("srgb"), RadiometryMethod::Srgb);
  EXPECT_EQ(*parseRadiometryMethod("stretch"), RadiometryMethod::Stretch);
  auto bad = parseRadiometryMethod("albedo");
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("--radiometry 'albedo'"), std::string::npos);
}

TEST(Radiometry, KnowsLandsatByItsProductAndSceneIds) {
  using L = LandsatLevel;
  EXPECT_EQ(landsatFromNames({"LC08_L1TP_038034_20150818_20200908_02_T1_B4.TIF"}), L::Level1);
  EXPECT_EQ(landsatFromNames({"LC09_L2SP_038034_20230815_20230817_02_T1_SR_B4.TIF"}), L::Level2);
  EXPECT_EQ(landsatFromNames({"/data/LC80380342015230LGN00/band4.tif"}), L::Level1);  // the directory
  EXPECT_EQ(landsatFromNames({"LC80380342015230LGN00_B4.TIF"}), L::Level1);
  EXPECT_EQ(landsatFromNames({"zion/landsat_b4.tif"}), L::Level1);
  EXPECT_EQ(landsatFromNames({"ortho_rgb16.tif"}), L::None);
  EXPECT_EQ(landsatFromNames({"CLC08.tif"}), L::None);  // not at a word start
}

ImageryValues values(float lo, float hi, double p1, double p99, bool integers = true) {
  return {lo, hi, p1, p99, integers};
}

TEST(Radiometry, AutoPicksSrgbReflectanceOrStretch) {
  const RadiometryOptions autoOpts;
  auto eight = chooseRadiometry(autoOpts, false, {"photo.tif"}, values(0, 255, 12, 240));
  ASSERT_TRUE(eight);
  EXPECT_EQ(eight->method, RadiometryMethod::Srgb);
  // The Zion sample's bands: Landsat 8 Level-1 digital numbers.
  auto zion = chooseRadiometry(autoOpts, false, {"landsat_b4.tif"}, values(5678, 25780, 6700, 18300));
  ASSERT_TRUE(zion);
  EXPECT_EQ(zion->method, RadiometryMethod::Reflectance);
  EXPECT_DOUBLE_EQ(zion->scale, 2.0e-5);
  EXPECT_DOUBLE_EQ(zion->offset, -0.1);
  auto level2 =
      chooseRadiometry(autoOpts, false, {"LC08_L2SP_038034_20150818_SR_B4.TIF"}, values(7300, 20000, 7600, 16000));
  ASSERT_TRUE(level2);
  EXPECT_EQ(level2->method, RadiometryMethod::Reflectance);
  EXPECT_DOUBLE_EQ(level2->scale, 2.75e-5);
  EXPECT_DOUBLE_EQ(level2->offset, -0.2);
  // 16-bit data without a sensor's name, or named Landsat but with values that are no
  // reflectance (a full-range 16-bit stretch): display stretch, with the reason.
  auto aerial = chooseRadiometry(autoOpts, false, {"ortho_rgb16.tif"}, values(0, 65535, 6700, 18300));
  ASSERT_TRUE(aerial);
  EXPECT_EQ(aerial->method, RadiometryMethod::Stretch);
  EXPECT_NE(aerial->why.find("not a known sensor"), std::string::npos);
  auto fullRange = chooseRadiometry(autoOpts, false, {"landsat_rgb.tif"}, values(0, 65535, 300, 64000));
  ASSERT_TRUE(fullRange);
  EXPECT_EQ(fullRange->method, RadiometryMethod::Stretch);
  auto floats = chooseRadiometry(autoOpts, false, {"landsat_b4.tif"}, values(5678, 25780, 6700, 18300, false));
  ASSERT_TRUE(floats);
  EXPECT_EQ(floats->method, RadiometryMethod::Stretch);
  // --stretch keeps today's behaviour.
  auto stretched = chooseRadiometry(autoOpts, true, {"landsat_b4.tif"}, values(5678, 25780, 6700, 18300));
  ASSERT_TRUE(stretched);
  EXPECT_EQ(stretched->method, RadiometryMethod::Stretch);
}

TEST(Radiometry, StatedChoicesWinAndContradictionsAreRefused) {
  RadiometryOptions o;
  o.method = RadiometryMethod::Reflectance;
  o.scale = 1e-4;
  o.offset = 0.0;
  auto r = chooseRadiometry(o, false, {"LC08_L2SP_x_SR_B4.TIF"}, values(0, 9000, 100, 8000));
  ASSERT_TRUE(r);
  EXPECT_EQ(r->method, RadiometryMethod::Reflectance);
  EXPECT_DOUBLE_EQ(r->scale, 1e-4);
  EXPECT_DOUBLE_EQ(r->offset, 0.0);
  o.method = RadiometryMethod::Srgb;
  auto srgb16 = chooseRadiometry(o, false, {"landsat_b4.tif"}, values(5678, 25780, 6700, 18300));
  ASSERT_FALSE(srgb16);
  EXPECT_NE(srgb16.error().message.find("--radiometry srgb"), std::string::npos);
  EXPECT_NE(srgb16.error().message.find("landsat_b4.tif"), std::string::npos);
  o.method = RadiometryMethod::Reflectance;
  auto both = chooseRadiometry(o, true, {"landsat_b4.tif"}, values(5678, 25780, 6700, 18300));
  ASSERT_FALSE(both);
  EXPECT_NE(both.error().message.find("--stretch"), std::string::npos);
}

// Chavez's dark-object subtraction: each band's dark object (its 0.01th percentile) less 1 %
// is the haze taken off every pixel; a band whose dark object is below 1 % keeps its values.
TEST(Radiometry, DarkObjectSubtractionTakesEachBandsHazeOff) {
  std::vector<float> rgb;
  // 20 000 pixels: band R from DN 8000 (ρ 0.06) up, G from 5600 (ρ 0.012) up, B all 9000; one
  // no-data pixel.
  for (int i = 0; i < 20000; ++i) {
    rgb.push_back(static_cast<float>(8000 + i));
    rgb.push_back(static_cast<float>(5600 + i));
    rgb.push_back(9000.0f);
  }
  rgb.insert(rgb.end(), {NAN, NAN, NAN});
  const auto dark = toSurfaceReflectance(rgb, 2e-5, -0.1);
  // The 0.01th percentile of 20 000 values is the 3rd smallest (index round(0.0001 · 19999) = 2).
  EXPECT_NEAR(dark[0], 8002 * 2e-5 - 0.1, 1e-6);
  EXPECT_NEAR(dark[1], 5602 * 2e-5 - 0.1, 1e-6);
  EXPECT_NEAR(dark[2], 9000 * 2e-5 - 0.1, 1e-6);
  const size_t p = 10000;  // DN 18000 in R
  EXPECT_NEAR(rgb[p * 3 + 0], (18000 * 2e-5 - 0.1) - (dark[0] - 0.01), 1e-6);
  EXPECT_NEAR(rgb[p * 3 + 1], std::max(0.0, (15600 * 2e-5 - 0.1) - (dark[1] - 0.01)), 1e-6);
  EXPECT_NEAR(rgb[p * 3 + 2], 0.01, 1e-6);  // a uniform band ends at the darkest object's 1 %
  EXPECT_TRUE(std::isnan(rgb[20000 * 3]));
}

TEST(Srgb, IsTheStandardsPiecewiseCurve) {
  EXPECT_EQ(srgbEncode8(0.0f), 0);
  EXPECT_EQ(srgbEncode8(1.0f), 255);
  EXPECT_EQ(srgbEncode8(0.05f), 63);  // a 5 % forest encodes near 63, not near 13
  EXPECT_EQ(srgbEncode8(0.002f), 7);  // the linear segment: 12.92 · 0.002 · 255 = 6.6
  EXPECT_NEAR(srgbEncode(0.18f), 0.4614f, 2e-4);
  for (int b = 0; b < 256; ++b) EXPECT_EQ(srgbEncode8(srgbDecode(static_cast<float>(b) / 255.0f)), b);
}

TEST(Deshading, SunVectorAndFlatGround) {
  const glm::dvec3 east = sunVectorEnu({90.0, 0.0});
  EXPECT_NEAR(east.x, 1.0, 1e-12);
  EXPECT_NEAR(east.y, 0.0, 1e-12);
  const glm::dvec3 s = sunVectorEnu({135.0, 60.0});
  EXPECT_NEAR(s.z, std::sin(60.0 * M_PI / 180.0), 1e-12);
  EXPECT_GT(s.x, 0.0);  // south-east
  EXPECT_LT(s.y, 0.0);
  EXPECT_FLOAT_EQ(deshadingGain({0, 0, 1}, s, 0.8), 1.0f);
  // A slope facing the sun is brighter than flat ground: its gain is below 1; one facing away
  // is darker: above 1; one in its own shadow gets the bound.
  const glm::dvec3 toSun = glm::normalize(glm::dvec3(s.x, s.y, 0.0) * 0.5 + glm::dvec3(0, 0, 1));
  EXPECT_LT(deshadingGain(toSun, s, 0.8), 1.0f);
  EXPECT_GT(deshadingGain(glm::dvec3(-toSun.x, -toSun.y, toSun.z), s, 0.8), 1.0f);
  EXPECT_FLOAT_EQ(deshadingGain(glm::normalize(glm::dvec3(-s.x, -s.y, 0.05)), s, 0.8), kMaxDeshadingGain);
}

// A plane rising 0.3 m per metre eastwards and 0.1 northwards, sampled on 10 m pixels.
TEST(Deshading, TileNormalsOfAPlane) {
  const int n = 16;
  std::vector<float> h(static_cast<size_t>(n * n));
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) h[static_cast<size_t>(j * n + i)] = static_cast<float>(100 + 3.0 * i - 1.0 * j);
  h[5 * n + 5] = NAN;
  const auto normals = tileNormals(h, n, 10.0);
  const glm::dvec3 expect = glm::normalize(glm::dvec3(-0.3, -0.1, 1.0));
  for (int k : {0, n - 1, 3 * n + 7, 4 * n + 5, 5 * n + 6, n * n - 1}) {
    EXPECT_NEAR(normals[static_cast<size_t>(k)].x, expect.x, 1e-5) << k;
    EXPECT_NEAR(normals[static_cast<size_t>(k)].y, expect.y, 1e-5) << k;
    EXPECT_NEAR(normals[static_cast<size_t>(k)].z, expect.z, 1e-5) << k;
  }
  EXPECT_EQ(normals[5 * n + 5], glm::vec3(0, 0, 1));  // nodata points up
}

// Samples of a terrain with every aspect (cones of slopes 5 … 35°), albedo varying from block
// to block and by ±5 % noise within, lit by a known sun.
std::vector<ShadingSample> litTerrain(const SunAngles& sun, double k, bool flat = false) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> aspect(0.0, 2.0 * M_PI), slope(5.0, 35.0), noise(-0.05, 0.05),
      blockAlbedo(0.05, 0.4);
  std::vector<ShadingSample> out;
  const glm::dvec3 s = sunVectorEnu(sun);
  for (uint32_t g = 0; g < 40; ++g) {
    const double albedo = blockAlbedo(rng);
    for (int i = 0; i < 500; ++i) {
      const double a = aspect(rng), t = flat ? 0.0 : slope(rng) * M_PI / 180.0;
      const glm::dvec3 n(std::sin(t) * std::sin(a), std::sin(t) * std::cos(a), std::cos(t));
      const double b = albedo * (1.0 + noise(rng)) * shading(n, s, k);
      out.push_back({glm::vec3(n), static_cast<float>(std::log(b)), g});
    }
  }
  return out;
}

TEST(SunEstimate, RecoversTheSunOfSyntheticTerrain) {
  for (const SunAngles truth : {SunAngles{135.0, 60.0}, SunAngles{250.0, 35.0}, SunAngles{20.0, 48.0}}) {
    const SunEstimate e = estimateSun(litTerrain(truth, 0.8), 0.8);
    ASSERT_TRUE(e.found) << e.note;
    const double dAz = std::remainder(e.sun.azimuthDeg - truth.azimuthDeg, 360.0);
    EXPECT_LT(std::abs(dAz), 2.0) << e.sun.azimuthDeg << " for " << truth.azimuthDeg;
    EXPECT_LT(std::abs(e.sun.elevationDeg - truth.elevationDeg), 3.0) << e.sun.elevationDeg;
    EXPECT_GT(e.explained, 0.5);
  }
}

TEST(SunEstimate, RefusesFlatTerrainAndUnshadedImagery) {
  const SunEstimate flat = estimateSun(litTerrain({135.0, 60.0}, 0.8, true), 0.8);
  EXPECT_FALSE(flat.found);
  EXPECT_NE(flat.note.find("too flat"), std::string::npos) << flat.note;
  // Sloped terrain whose brightness has no shading in it (k = 0): nothing explains it.
  const SunEstimate unlit = estimateSun(litTerrain({135.0, 60.0}, 0.0), 0.8);
  EXPECT_FALSE(unlit.found);
  EXPECT_NE(unlit.note.find("explains only"), std::string::npos) << unlit.note;
}

DatasetMeta metaWith(std::optional<RadiometryRecord> r) {
  DatasetMeta m;
  m.name = "r";
  m.bounds = {-113.2, 37.1, -112.9, 37.5};
  m.imagery = ImageryFormat::Jpeg;
  m.imageryDatetime = "2015-08-18T17:58:00Z";
  m.radiometry = std::move(r);
  return m;
}

std::string jsonText(const DatasetMeta& m) {
  const fs::path d = vegstream::testing::testOutputDir();
  EXPECT_TRUE(writeDatasetMeta(d, m));
  std::stringstream ss;
  ss << std::ifstream(d / "dataset.json").rdbuf();
  return ss.str();
}

TEST(RadiometryRecord, RoundTripsThroughDatasetJsonAndIsOptional) {
  RadiometryRecord r;
  r.method = "reflectance";
  r.scale = 2e-5;
  r.offset = -0.1;
  r.darkObject = std::array<double, 3>{0.0218, 0.0334, 0.0551};
  r.darkObjectPercentile = 0.01;
  r.darkObjectReflectance = 0.01;
  r.deshading = DeshadingRecord{"imagery datetime", 133.25, 61.5, 0.8, "NOAA"};
  const std::string text = jsonText(metaWith(r));
  EXPECT_NE(text.find("\"radiometry\""), std::string::npos) << text;
  auto back = parseDatasetMeta(text, "x.json");
  ASSERT_TRUE(back) << back.error().message;
  EXPECT_EQ(back->imageryDatetime, "2015-08-18T17:58:00Z");
  ASSERT_TRUE(back->radiometry);
  EXPECT_EQ(back->radiometry->method, "reflectance");
  EXPECT_EQ(back->radiometry->scale, 2e-5);
  EXPECT_EQ(back->radiometry->offset, -0.1);
  EXPECT_EQ(back->radiometry->darkObject, r.darkObject);
  ASSERT_TRUE(back->radiometry->deshading);
  EXPECT_EQ(back->radiometry->deshading->source, "imagery datetime");
  EXPECT_EQ(back->radiometry->deshading->sunAzimuthDeg, 133.25);
  EXPECT_EQ(back->radiometry->deshading->sunElevationDeg, 61.5);
  EXPECT_EQ(back->radiometry->deshading->directFraction, 0.8);
  // A dataset.json from before the key: no record, and it still reads.
  auto old = parseDatasetMeta(jsonText(metaWith(std::nullopt)), "old.json");
  ASSERT_TRUE(old) << old.error().message;
  EXPECT_FALSE(old->radiometry);
}

TEST(RadiometryRecord, BadFieldsAreNamed) {
  RadiometryRecord r;
  r.method = "srgb";
  r.deshading = DeshadingRecord{"estimated", 10.0, 40.0, 0.8, ""};
  const std::string text = jsonText(metaWith(r));
  const auto errorWith = [&](const std::string& from, const std::string& to) {
    std::string t = text;
    const auto at = t.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) t.replace(at, from.size(), to);
    auto m = parseDatasetMeta(t, "d.json");
    return m ? std::string("(read)") : m.error().message;
  };
  EXPECT_NE(errorWith("\"method\": \"srgb\"", "\"method\": \"gamma\"").find("imagery.radiometry.method"),
            std::string::npos);
  EXPECT_NE(errorWith("\"source\": \"estimated\"", "\"source\": \"guess\"").find("imagery.radiometry.deshading.source"),
            std::string::npos);
  EXPECT_NE(errorWith("\"sun_elevation_deg\": 40.0", "\"sun_elevation_deg\": 140").find("sun_elevation_deg"),
            std::string::npos);
}

}  // namespace
}  // namespace vegstream::datasets
