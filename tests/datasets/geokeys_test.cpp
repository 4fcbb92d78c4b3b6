// decodeGeoKeys on key directories copied from the sample files and on broken ones.

#include "datasets/geokeys.h"

#include <gtest/gtest.h>

namespace vegstream::datasets {
namespace {

TEST(GeoKeys, LandsatUtmDirectory) {
  // zion/landsat_b4.tif's tag 34735 and 34737, as GDAL wrote them.
  const std::vector<double> dir = {1,    1,     0, 7,  1024, 0, 1, 1,    1025, 0, 1, 1,     1026, 34737, 33, 0,
                                   2049, 34737, 7, 33, 2054, 0, 1, 9102, 3072, 0, 1, 32612, 3076, 0,     1,  9001};
  const auto keys = decodeGeoKeys(dir, {}, "UTM Zone 12, Northern Hemisphere|WGS 84|");
  ASSERT_TRUE(keys.has_value());
  EXPECT_EQ(keys->modelType, 1);
  EXPECT_EQ(keys->rasterType, 1);
  EXPECT_EQ(keys->epsg(), 32612);
  EXPECT_EQ(keys->description(), "UTM Zone 12, Northern Hemisphere; WGS 84");
}

TEST(GeoKeys, GoletaDirectoryClaimsMoreKeysThanItHolds) {
  // goleta/sba_elev32_wgs84_512x512.tif: the header says 7 keys, 6 follow.
  const std::vector<double> dir = {1, 1,    0,    7, 1024, 0,    1,    2, 1025, 0,    1,    1, 2048, 0,
                                   1, 4326, 2054, 0, 1,    9102, 4096, 0, 1,    5030, 4099, 0, 1,    9001};
  EXPECT_FALSE(decodeGeoKeys(dir, {}, "").has_value());
}

TEST(GeoKeys, ModelTypePicksTheCode) {
  // Both codes present: GTModelType decides which names the raster's CRS.
  std::vector<double> dir = {1, 1, 0, 3, 1024, 0, 1, 2, 2048, 0, 1, 4269, 3072, 0, 1, 26912};
  EXPECT_EQ(decodeGeoKeys(dir, {}, "")->epsg(), 4269);
  dir[7] = 1;
  EXPECT_EQ(decodeGeoKeys(dir, {}, "")->epsg(), 26912);
}

TEST(GeoKeys, UserDefinedHasNoCode) {
  const std::vector<double> dir = {1, 1, 0, 2, 1024, 0, 1, 1, 3072, 0, 1, 32767};
  EXPECT_EQ(decodeGeoKeys(dir, {}, "")->epsg(), 0);
}

TEST(GeoKeys, ValuesOutsideTheirParameterTagAreCorrupt) {
  const std::vector<double> ascii = {1, 1, 0, 1, 1026, 34737, 50, 0};
  EXPECT_FALSE(decodeGeoKeys(ascii, {}, "short|").has_value());
  const std::vector<double> dbl = {1, 1, 0, 1, 2057, 34736, 1, 3};
  EXPECT_FALSE(decodeGeoKeys(dbl, {6378137.0}, "").has_value());
  const std::vector<double> unknownTag = {1, 1, 0, 1, 2048, 999, 1, 0};
  EXPECT_FALSE(decodeGeoKeys(unknownTag, {}, "").has_value());
  EXPECT_FALSE(decodeGeoKeys({2, 1, 0, 0}, {}, "").has_value());  // unknown version
}

}  // namespace
}  // namespace vegstream::datasets
