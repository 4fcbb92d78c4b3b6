#include "geo/projection.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

namespace vegstream::geo {
namespace {

// Reference eastings / northings come from an independent evaluation of Karney's 6th-order
// Krüger series (Python, written for these tests), which agrees with GeographicLib to ~nm.
constexpr double kUtmTolM = 1e-5;

TEST(Projection, GeographicIsLonLat) {
  auto xy = toProjected(wgs84Crs(), Geodetic{37.3, -113.05, 1000.0});
  ASSERT_TRUE(xy.ok());
  EXPECT_DOUBLE_EQ(xy->x, -113.05);
  EXPECT_DOUBLE_EQ(xy->y, 37.3);
  const Geodetic back = fromProjected(wgs84Crs(), *xy, 12.5);
  EXPECT_DOUBLE_EQ(back.latDeg, 37.3);
  EXPECT_DOUBLE_EQ(back.lonDeg, -113.05);
  EXPECT_DOUBLE_EQ(back.heightM, 12.5);
}

TEST(Projection, WebMercatorKnownValues) {
  EXPECT_NEAR(std::numbers::pi * 6378137.0, kWebMercatorHalfWorldM, 1e-8);
  auto east = toProjected(webMercatorCrs(), Geodetic{0.0, 180.0, 0.0});
  ASSERT_TRUE(east.ok());
  EXPECT_NEAR(east->x, 20037508.342789244, 1e-6);
  EXPECT_NEAR(east->y, 0.0, 1e-9);
  auto edge = toProjected(webMercatorCrs(), Geodetic{kWebMercatorMaxLatDeg, -180.0, 0.0});
  ASSERT_TRUE(edge.ok());
  EXPECT_NEAR(edge->x, -20037508.342789244, 1e-6);
  EXPECT_NEAR(edge->y, 20037508.342789244, 1e-4);  // the pyramid is square at ±85.0511°
  // 45°N: y = a·ln(tan(67.5°)) = 5 621 521.486 m.
  auto mid = toProjected(webMercatorCrs(), Geodetic{45.0, 0.0, 0.0});
  ASSERT_TRUE(mid.ok());
  EXPECT_NEAR(mid->y, 5621521.486192066, 1e-6);
}

TEST(Projection, WebMercatorRefusesPolarLatitudes) {
  for (double lat : {85.06, -85.06, 89.0, 90.0}) {
    auto xy = toProjected(webMercatorCrs(), Geodetic{lat, 10.0, 0.0});
    ASSERT_FALSE(xy.ok()) << lat;
    EXPECT_EQ(xy.error().kind, ErrorKind::InvalidInput);
    EXPECT_NE(xy.error().message.find("85.0511"), std::string::npos) << xy.error().message;
    EXPECT_NE(xy.error().message.find("EPSG:3857"), std::string::npos);
  }
  EXPECT_TRUE(toProjected(webMercatorCrs(), Geodetic{85.0511, 10.0, 0.0}).ok());
}

TEST(Projection, RejectsNonFiniteAndBadLatitude) {
  EXPECT_FALSE(toProjected(wgs84Crs(), Geodetic{std::nan(""), 0.0, 0.0}).ok());
  EXPECT_FALSE(toProjected(utmCrs(12, true), Geodetic{0.0, INFINITY, 0.0}).ok());
  auto bad = toProjected(wgs84Crs(), Geodetic{91.0, 0.0, 0.0});
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("lat 91"), std::string::npos) << bad.error().message;
}

TEST(Projection, UtmKnownValues) {
  // Zion, zone 12N.
  auto zion = toProjected(utmCrs(12, true), Geodetic{37.3, -113.05, 0.0});
  ASSERT_TRUE(zion.ok());
  EXPECT_NEAR(zion->x, 318307.774530, kUtmTolM);
  EXPECT_NEAR(zion->y, 4130123.378052, kUtmTolM);
  // Namibia, zone 33S (false northing 10 000 km).
  auto namibia = toProjected(utmCrs(33, false), Geodetic{-22.5, 17.1, 0.0});
  ASSERT_TRUE(namibia.ok());
  EXPECT_NEAR(namibia->x, 716030.129249, kUtmTolM);
  EXPECT_NEAR(namibia->y, 7510312.862623, kUtmTolM);
  // On the central meridian the easting is exactly the false easting.
  auto central = toProjected(utmCrs(12, true), Geodetic{10.0, -111.0, 0.0});
  ASSERT_TRUE(central.ok());
  EXPECT_NEAR(central->x, 500000.0, 1e-9);
}

TEST(Projection, UtmForcedZoneOutsideItsStrip) {
  // -108.2° is in zone 12's eastern neighbour (zone 13 starts at -108°): still zone 12's grid.
  auto xy = toProjected(utmCrs(12, true), Geodetic{37.3, -108.2, 0.0});
  ASSERT_TRUE(xy.ok());
  EXPECT_NEAR(xy->x, 748177.266711, kUtmTolM);
  EXPECT_NEAR(xy->y, 4131829.644403, kUtmTolM);
  // Far outside (18° from the central meridian): PROJ's extended transverse Mercator still
  // maps it, and back to within a millimetre.
  auto far = toProjected(utmCrs(12, true), Geodetic{37.3, -95.0, 0.0});
  ASSERT_TRUE(far.ok());
  EXPECT_GT(far->x, 1500000.0);  // 1923 km: far beyond the zone's 1000 km
  const Geodetic back = fromProjected(utmCrs(12, true), *far);
  EXPECT_NEAR(back.latDeg, 37.3, 1e-8);
  EXPECT_NEAR(back.lonDeg, -95.0, 1e-8);
}

TEST(Projection, UtmHemisphereIsTheCrsNotThePoint) {
  // 0.1°S in a northern CRS: northing continues below the equator (negative).
  auto xy = toProjected(utmCrs(12, true), Geodetic{-0.1, -111.0, 0.0});
  ASSERT_TRUE(xy.ok());
  EXPECT_NEAR(xy->y, -11053.004724, kUtmTolM);
  const Geodetic back = fromProjected(utmCrs(12, true), *xy);
  EXPECT_NEAR(back.latDeg, -0.1, 1e-11);
  // And 0.1°N in a southern CRS: just above 10 000 km.
  auto south = toProjected(utmCrs(12, false), Geodetic{0.1, -111.0, 0.0});
  ASSERT_TRUE(south.ok());
  EXPECT_NEAR(south->y, 10000000.0 + 11053.004724, kUtmTolM);
}

TEST(Projection, ReprojectUtmToWebMercator) {
  const Crs utm = utmCrs(12, true);
  auto merc = reproject(utm, webMercatorCrs(), glm::dvec2(318307.774530, 4130123.378052));
  ASSERT_TRUE(merc.ok());
  auto expected = toProjected(webMercatorCrs(), Geodetic{37.3, -113.05, 0.0});
  ASSERT_TRUE(expected.ok());
  EXPECT_NEAR(merc->x, expected->x, 1e-4);
  EXPECT_NEAR(merc->y, expected->y, 1e-4);
  auto same = reproject(utm, utm, glm::dvec2(1.0, 2.0));
  ASSERT_TRUE(same.ok());
  EXPECT_EQ(same->x, 1.0);
}

}  // namespace
}  // namespace vegstream::geo
