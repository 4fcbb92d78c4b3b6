// The Zion sample imported as `vegstream import` does by default (radiometry auto → Landsat
// reflectance, de-shaded under the sun of --imagery-datetime): the tiles hold the ground's
// surface reflectance (issue 39, item 4), checked over the footprint of a nadir view at three
// places against the reflectance computed here from the bands (zion_ground_colour.h).

#include <gtest/gtest.h>

#include <cstdio>

#include "geo/datetime.h"
#include "geo/solar_position.h"
#include "import_test_util.h"
#include "zion_ground_colour.h"

namespace vegstream::datasets {
namespace {
using namespace vegstream::datasets::test;
using vegstream::testing::ciede2000;

const std::string kZion = samples() + "/zion/";
constexpr const char* kWhen = "2015-08-18T17:58:00Z";  // LC80380342015230LGN00's acquisition

// The meadow and slickrock of issue 39, and a dense conifer stand on the Kolob plateau (its
// densest green in the bands over 37.48–37.50 N, 113.00–113.03 W: the footprint of highest NDVI
// less twice its red reflectance, NDVI 0.44 from the raw bands 5 and 4).
const Place kPlaces[] = {
    {"Kolob meadow", 37.4815, -113.0095}, {"Kolob forest", 37.4940, -113.0080}, {"slickrock", 37.1907, -112.9185}};

Result<fs::path> zionImport(const std::string& name, const std::string& args) {
  return testing::cachedFixture(name, testing::vegstreamKey(), [args](const fs::path& out) -> Status {
    const auto r = testing::runVegstream("import --dem " + kZion + "srtm.tif --imagery-bands " + kZion +
                                         "landsat_b4.tif," + kZion + "landsat_b3.tif," + kZion +
                                         "landsat_b2.tif --height-resampling cubic " + args + " --out " + out.string());
    if (r.exitCode != 0)
      return makeError(ErrorKind::Internal, "vegstream import: exit " + std::to_string(r.exitCode) + ": " + r.err);
    return {};
  });
}

class ZionReflectance : public ::testing::Test {
 protected:
  void SetUp() override {
    auto dir = zionImport("zion-reflectance", std::string("--imagery-datetime ") + kWhen);
    ASSERT_TRUE(dir.ok()) << dir.error().message;
    dir_ = *dir;
    auto meta = readDatasetMeta(dir_);
    ASSERT_TRUE(meta) << meta.error().message;
    meta_ = *meta;
  }
  fs::path dir_;
  DatasetMeta meta_;
};

TEST_F(ZionReflectance, DatasetJsonRecordsTheRadiometryAndTheSun) {
  ASSERT_TRUE(meta_.radiometry);
  const RadiometryRecord& r = *meta_.radiometry;
  EXPECT_EQ(r.method, "reflectance");
  EXPECT_DOUBLE_EQ(r.scale.value_or(0), 2e-5);
  EXPECT_DOUBLE_EQ(r.offset.value_or(0), -0.1);
  const LandsatReflectance truth(kZion);
  ASSERT_TRUE(truth.ok());
  ASSERT_TRUE(r.darkObject);
  for (size_t c = 0; c < 3; ++c)  // haze = dark object − 1 % (when above it)
    EXPECT_NEAR(std::max(0.0, (*r.darkObject)[c] - 0.01), truth.haze()[c], 1e-6) << "band " << c;
  EXPECT_EQ(meta_.imageryDatetime, kWhen);
  ASSERT_TRUE(r.deshading);
  EXPECT_EQ(r.deshading->source, "imagery datetime");
  const auto t = geo::parseIsoDateTime(kWhen);
  ASSERT_TRUE(t);
  const glm::dvec2 c = meta_.bounds.centre();
  const geo::SolarPosition sun = geo::solarPosition(t->unixMs, c.y, c.x);
  EXPECT_NEAR(r.deshading->sunAzimuthDeg, sun.azimuthDeg, 1e-9);
  EXPECT_NEAR(r.deshading->sunElevationDeg, sun.elevationDeg, 1e-9);
  EXPECT_GT(sun.elevationDeg, 50.0);  // a late-morning summer sun over Utah
}

// Issue 39: near (74, 68, 50) meadow, (42, 45, 31) forest, (98, 79, 65) slickrock. Three
// imports of the same bands: the default (reflectance, de-shaded), --deshading off (the
// radiometry alone) and --stretch p1,p99 (the old tiles). The radiometry alone matches the
// ground's reflectance everywhere; the de-shaded albedo does where the ground is flat, and lit
// again by the acquisition sun over the imported heights (what a renderer at that time shows)
// matches it everywhere.
TEST_F(ZionReflectance, TilesHoldTheGroundsSurfaceReflectance) {
  const LandsatReflectance truth(kZion);
  ASSERT_TRUE(truth.ok());
  auto shaded = zionImport("zion-reflectance-shaded", "--deshading off");
  auto old = zionImport("zion-stretched", "--stretch p1,p99");
  ASSERT_TRUE(shaded.ok()) << shaded.error().message;
  ASSERT_TRUE(old.ok()) << old.error().message;
  auto shadedMeta = readDatasetMeta(*shaded), oldMeta = readDatasetMeta(*old);
  ASSERT_TRUE(shadedMeta && oldMeta);
  ASSERT_TRUE(meta_.radiometry && meta_.radiometry->deshading);
  const DeshadingRecord d = *meta_.radiometry->deshading;
  const double az = d.sunAzimuthDeg * M_PI / 180.0, el = d.sunElevationDeg * M_PI / 180.0;
  const Relight sun{{std::sin(az) * std::cos(el), std::cos(az) * std::cos(el), std::sin(el)}, d.directFraction};
  std::printf("%-13s %-15s | %-19s | %-23s | %-23s | %s\n", "place", "reflectance", "old stretched tiles",
              "reflectance, shaded", "albedo (de-shaded)", "albedo relit");
  for (const Place& p : kPlaces) {
    const LinearRgb want = truth.footprintMean(p);
    const LinearRgb got[4] = {tileFootprintMean(*old, *oldMeta, p), tileFootprintMean(*shaded, *shadedMeta, p),
                              tileFootprintMean(dir_, meta_, p), tileFootprintMean(dir_, meta_, p, sun)};
    ASSERT_GT(want.pixels, 20) << p.name;
    double dE[4];
    std::array<int, 3> c[4];
    for (int k = 0; k < 4; ++k) {
      ASSERT_GT(got[k].pixels, 20) << p.name;
      dE[k] = ciede2000(want.lab(), got[k].lab());
      c[k] = got[k].srgb8();
    }
    const auto w = want.srgb8();
    std::printf(
        "%-13s (%3d, %3d, %3d) | (%3d, %3d, %3d) %5.2f | (%3d, %3d, %3d) dE %5.2f | (%3d, %3d, %3d) dE %5.2f | "
        "(%3d, %3d, %3d) dE %5.2f\n",
        p.name, w[0], w[1], w[2], c[0][0], c[0][1], c[0][2], dE[0], c[1][0], c[1][1], c[1][2], dE[1], c[2][0], c[2][1],
        c[2][2], dE[2], c[3][0], c[3][1], c[3][2], dE[3]);
    EXPECT_LE(dE[1], 3.0) << p.name << ": the radiometry alone";
    EXPECT_LE(dE[3], 3.0) << p.name << ": the albedo lit by the acquisition sun";
    if (std::string(p.name) != "slickrock") {
      EXPECT_LE(dE[2], 3.0) << p.name << ": the albedo of flat ground";
    }
  }
}

// What the tiles held before: the forest's display stretch put it near black in linear light.
TEST_F(ZionReflectance, TheStretchedTilesWereFarFromIt) {
  const LandsatReflectance truth(kZion);
  ASSERT_TRUE(truth.ok());
  auto old = zionImport("zion-stretched", "--stretch p1,p99");
  ASSERT_TRUE(old.ok()) << old.error().message;
  auto oldMeta = readDatasetMeta(*old);
  ASSERT_TRUE(oldMeta);
  ASSERT_TRUE(oldMeta->radiometry);
  EXPECT_EQ(oldMeta->radiometry->method, "stretch");
  EXPECT_EQ(oldMeta->radiometry->deshading.value_or(DeshadingRecord{}).source, "none");
  const Place& forest = kPlaces[1];
  EXPECT_GT(ciede2000(truth.footprintMean(forest).lab(), tileFootprintMean(*old, *oldMeta, forest).lab()), 10.0);
}

}  // namespace
}  // namespace vegstream::datasets
