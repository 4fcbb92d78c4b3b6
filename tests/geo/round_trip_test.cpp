// Round trips through every coordinate system geo/ offers: lat/lon → UTM → lat/lon → Web
// Mercator → lat/lon → local ENU → lat/lon, each leg and the whole chain below 1 mm, across
// zones and both hemispheres, including points outside their CRS's own zone.

#include <algorithm>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "geo/local_frame.h"
#include "geo/projection.h"
#include "geo/xyz_tiles.h"
#include "geo_test_util.h"

namespace vegstream::geo {
namespace {

constexpr double kMillimetre = 1e-3;

struct Case {
  const char* what;
  Geodetic p;
  Crs utm;
};

std::vector<Case> cases() {
  return {
      {"Zion, 12N", {37.3, -113.05, 1500.0}, utmCrs(12, true)},
      {"Namibia, 33S", {-22.5, 17.1, 1100.0}, utmCrs(33, false)},
      {"west edge of 12N", {40.0, -113.9999, 0.0}, utmCrs(12, true)},
      {"zone 13 forced into 12N", {38.5, -107.5, 2500.0}, utmCrs(12, true)},
      {"zone 11 forced into 12N", {36.0, -115.8, 600.0}, utmCrs(12, true)},
      {"zone 34 forced into 33S", {-33.9, 18.4, 10.0}, utmCrs(33, false)},
      {"south of the equator in 12N", {-0.5, -111.7, 0.0}, utmCrs(12, true)},
      {"north of the equator in 33S", {0.5, 14.2, 0.0}, utmCrs(33, false)},
      {"Tromsø, 34N", {69.65, 18.96, 50.0}, utmCrs(34, true)},
      {"Tierra del Fuego, 19S", {-54.8, -68.3, 30.0}, utmCrs(19, false)},
      {"antimeridian, 60N", {-16.5, 179.9, 0.0}, utmCrs(60, false)},
      {"Dead Sea, below the ellipsoid", {31.5, 35.5, -430.0}, utmCrs(36, true)},
  };
}

TEST(RoundTrip, EveryLegAndTheChainBelowAMillimetre) {
  const Crs merc = webMercatorCrs();
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.what);
    auto utm = toProjected(c.utm, c.p);
    ASSERT_TRUE(utm.ok()) << utm.error().message;
    const Geodetic fromUtm = fromProjected(c.utm, *utm, c.p.heightM);
    EXPECT_LT(test::metresBetween(c.p, fromUtm), kMillimetre);

    auto m = toProjected(merc, fromUtm);
    ASSERT_TRUE(m.ok()) << m.error().message;
    const Geodetic fromMerc = fromProjected(merc, *m, fromUtm.heightM);
    EXPECT_LT(test::metresBetween(fromUtm, fromMerc), kMillimetre);

    // The frame sits 30 km away, as a dataset centre would.
    const LocalFrame frame(test::travel(c.p, 45.0, 30000.0, 1000.0));
    const Geodetic fromEnu = frame.toGeodetic(frame.toLocal(fromMerc));
    EXPECT_LT(test::metresBetween(fromMerc, fromEnu), kMillimetre);

    // And the whole chain, reverse direction included: ENU → UTM → lat/lon.
    EXPECT_LT(test::metresBetween(c.p, fromEnu), kMillimetre);
    auto utm2 = toProjected(c.utm, fromEnu);
    ASSERT_TRUE(utm2.ok());
    EXPECT_LT(std::hypot(utm2->x - utm->x, utm2->y - utm->y), kMillimetre);
  }
}

TEST(RoundTrip, UtmAllZonesBothHemispheresAndNeighbours) {
  // 6000 draws: every zone, both hemispheres, up to 1.5 zone widths beyond the zone's own
  // strip (data are delivered in one zone across boundaries).
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double worst = 0.0;
  int converted = 0;
  for (int zone = 1; zone <= 60; ++zone) {
    for (int i = 0; i < 100; ++i) {
      const bool north = (i % 2) == 0;
      const double lat = north ? 84.0 * unit(rng) : -80.0 * unit(rng);
      const double centralLon = -183.0 + 6.0 * zone;
      const double lon = centralLon + (unit(rng) - 0.5) * 2.0 * 9.0;
      const Crs crs = utmCrs(zone, north);
      const Geodetic p{lat, lon, 0.0};
      auto xy = toProjected(crs, p);
      if (!xy.ok()) continue;  // beyond 1000 km easting near the equator: refused, fine
      ++converted;
      worst = std::max(worst, test::metresBetween(p, fromProjected(crs, *xy)));
    }
  }
  // Points whose easting would pass 1000 km (low latitudes, far from the central meridian)
  // are refused by UTMUPS; about 3/4 of the draws are in range.
  EXPECT_GT(converted, 4000);
  EXPECT_LT(worst, kMillimetre);
  EXPECT_LT(worst, 1e-6);  // GeographicLib's series is good to nanometres here
}

TEST(RoundTrip, WebMercatorAndTilePixelsAcrossTheWorld) {
  std::mt19937_64 rng(777);
  std::uniform_real_distribution<double> lonD(-180.0, 180.0);
  std::uniform_real_distribution<double> latD(-85.0, 85.0);
  double worstMerc = 0.0;
  double worstPixel = 0.0;
  for (int i = 0; i < 2000; ++i) {
    const Geodetic p{latD(rng), lonD(rng), 0.0};
    auto m = toProjected(webMercatorCrs(), p);
    ASSERT_TRUE(m.ok());
    worstMerc = std::max(worstMerc, test::metresBetween(p, fromProjected(webMercatorCrs(), *m)));
    // Through a zoom-18 tile's pixel coordinates.
    const TileId t = tileContaining({p.lonDeg, p.latDeg}, 18);
    const glm::dvec2 px = lonLatToPixel(t, {p.lonDeg, p.latDeg}, 512);
    EXPECT_GE(px.x, 0.0);
    EXPECT_LE(px.x, 512.0);
    const glm::dvec2 ll = pixelToLonLat(t, px, 512);
    worstPixel = std::max(worstPixel, test::metresBetween(p, Geodetic{ll.y, ll.x, 0.0}));
  }
  EXPECT_LT(worstMerc, kMillimetre);
  EXPECT_LT(worstPixel, kMillimetre);
}

}  // namespace
}  // namespace vegstream::geo
