// The other real samples through `vegstream import`: goleta (corrupt DEM GeoKeys: refused
// without --dem-crs, imported with it; its RGB's keys are sound), rmnp (DEM and imagery of
// different extents and pixel sizes) and the XYZ form on grandcanyon-xyz.

#include <gtest/gtest.h>

#include "import_test_util.h"

namespace vegstream::datasets {
namespace {
using namespace vegstream::datasets::test;
using vegstream::testing::countLines;
using vegstream::testing::runVegstream;

const std::string kGoletaDem = samples() + "/goleta/sba_elev32_wgs84_512x512.tif";
const std::string kGoletaRgb = samples() + "/goleta/sba_rgb_wgs84_512x512.tif";

TEST(ImportSamples, GoletaWithoutDemCrsIsRefusedClearly) {
  const fs::path parent = importTmp("goleta_refused");
  const auto r =
      runVegstream("import --dem " + kGoletaDem + " --imagery " + kGoletaRgb + " --out " + (parent / "g").string());
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_EQ(countLines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("sba_elev32_wgs84_512x512.tif"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--dem-crs"), std::string::npos) << r.err;
  EXPECT_EQ(entriesIn(parent), 0);
}

TEST(ImportSamples, GoletaWithDemCrsImports) {
  const fs::path out = importTmp("goleta") / "g";
  const auto r = runVegstream("import --dem " + kGoletaDem + " --dem-crs EPSG:4326 --imagery " + kGoletaRgb +
                              " --out " + out.string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  auto meta = readDatasetMeta(out);
  ASSERT_TRUE(meta) << meta.error().message;
  EXPECT_EQ(meta->maxZoom, 16);  // 2.8 m pixels → the first zoom at least as fine: 2.0 m
  EXPECT_NEAR(meta->minHeightM, 2.5, 0.5);
  EXPECT_NEAR(meta->maxHeightM, 20.7, 0.5);
  EXPECT_EQ(meta->imageryTiles, meta->elevationTiles);
  EXPECT_GE(meta->elevationTiles, 20u);
  EXPECT_NEAR(meta->bounds.westDeg, -119.8337, 1e-3);
  EXPECT_NEAR(meta->bounds.northDeg, 34.4448, 1e-3);
  // Colour came through: the airport photo is neither black nor uniform.
  DatasetSampler s(out, *meta);
  const auto c = s.colour(-119.826, 34.437);
  ASSERT_TRUE(c.has_value());
  EXPECT_GT((*c)[0] + (*c)[1] + (*c)[2], 60);
}

TEST(ImportSamples, RmnpDifferentExtentsAndPixelSizes) {
  const fs::path out = importTmp("rmnp") / "r";
  const auto r = runVegstream("import --dem " + samples() + "/rmnp/rmnp-dem.tif --imagery " + samples() +
                              "/rmnp/rmnp-rgb.tif --imagery-format png --out " + out.string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  auto meta = readDatasetMeta(out);
  ASSERT_TRUE(meta) << meta.error().message;
  // Max zoom from the finer imagery (127 m → zoom 10, 117 m), not the DEM (234 m → zoom 9).
  EXPECT_EQ(meta->maxZoom, 10);
  EXPECT_GE(meta->minHeightM, 2281.0 - 0.5);
  EXPECT_LE(meta->maxHeightM, 4261.0 + 0.5);
  EXPECT_GT(meta->maxHeightM, 4100.0);
  EXPECT_EQ(meta->imagery, ImageryFormat::Png);
  EXPECT_EQ(meta->imageryTiles, meta->elevationTiles);  // the larger imagery covers every DEM tile
  // The dataset's extent is the DEM's, not the larger imagery's.
  EXPECT_NEAR(meta->bounds.westDeg, -105.94, 0.3);
  DatasetSampler s(out, *meta);
  int withColour = 0;
  for (int k = 0; k < 10; ++k) {
    const double lon = meta->bounds.westDeg + (k + 0.5) / 10.0 * meta->bounds.widthDeg();
    withColour += s.colour(lon, meta->bounds.centre().y).has_value();
  }
  EXPECT_EQ(withColour, 10);
}

TEST(ImportSamples, XyzFormImportsGrandCanyon) {
  const fs::path out = importTmp("grandcanyon") / "gc";
  const auto r =
      runVegstream("import --xyz-elevation '" + samples() +
                   "/grandcanyon-xyz/terrain-rgb/{z}/{x}/{y}.png' --encoding terrain-rgb --out " + out.string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  auto meta = readDatasetMeta(out);
  ASSERT_TRUE(meta) << meta.error().message;
  EXPECT_EQ(meta->maxZoom, 12);
  EXPECT_GE(meta->minHeightM, 439.0 - 0.1);
  EXPECT_LE(meta->maxHeightM, 2184.0 + 0.5);  // README rounds: decoded maximum 2184.4
}

}  // namespace
}  // namespace vegstream::datasets
