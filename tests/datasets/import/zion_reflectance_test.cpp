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
// darkest green patch in the bands near 37.48–37.50 N, 113.00–113.03 W).
const Place kPlaces[] = {{"Kolob meadow", 37.4815, -113.0095},
                         {"Kolob forest", 37.4900, -113.0200},
                         {"slickrock", 37.1907, -112.9185}};

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

// Issue 39: near (74, 68, 50) meadow, (42, 45, 31) forest, (98, 79, 65) slickrock.
TEST_F(ZionReflectance, TilesHoldTheGroundsSurfaceReflectance) {
  const LandsatReflectance truth(kZion);
  ASSERT_TRUE(truth.ok());
  auto old = zionImport("zion-stretched", "--stretch p1,p99");
  ASSERT_TRUE(old.ok()) << old.error().message;
  auto oldMeta = readDatasetMeta(*old);
  ASSERT_TRUE(oldMeta);
  for (const Place& p : kPlaces) {
    const LinearRgb want = truth.footprintMean(p), got = tileFootprintMean(dir_, meta_, p),
                    before = tileFootprintMean(*old, *oldMeta, p);
    ASSERT_GT(want.pixels, 20) << p.name;
    ASSERT_GT(got.pixels, 20) << p.name;
    const double dE = ciede2000(want.lab(), got.lab()), dEBefore = ciede2000(want.lab(), before.lab());
    const auto w = want.srgb8(), g = got.srgb8(), b = before.srgb8();
    std::printf("%-13s reflectance (%d, %d, %d) | tiles (%d, %d, %d) dE00 %.2f | stretched tiles (%d, %d, %d) dE00 %.2f\n",
                p.name, w[0], w[1], w[2], g[0], g[1], g[2], dE, b[0], b[1], b[2], dEBefore);
    EXPECT_LE(dE, 3.0) << p.name;
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
