#include "geo/local_frame.h"

#include <cmath>

#include <GeographicLib/Constants.hpp>
#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "geo_test_util.h"

namespace vegstream::geo {
namespace {

const Geodetic kZion{37.3, -113.05, 1200.0};

TEST(LocalFrame, OriginIsZero) {
  const LocalFrame frame(kZion);
  const glm::dvec3 o = frame.toLocal(kZion);
  EXPECT_NEAR(glm::length(o), 0.0, 1e-9);
}

TEST(LocalFrame, EarthCurvatureTwentyKilometresEast) {
  const Geodetic origin{37.3, -113.05, 0.0};
  const LocalFrame frame(origin);
  const glm::dvec3 p = frame.toLocal(test::travel(origin, 90.0, 20000.0, 0.0));
  // Drop below the tangent plane: d² / (2N), N the east-west radius of curvature (6386.0 km at
  // 37.3°N) — 31.32 m (31.4 m on a 6371 km sphere).
  const double a = GeographicLib::Constants::WGS84_a();
  const double f = GeographicLib::Constants::WGS84_f();
  const double s = std::sin(origin.latDeg * std::acos(-1.0) / 180.0);
  const double n = a / std::sqrt(1.0 - f * (2.0 - f) * s * s);
  EXPECT_NEAR(p.z, -20000.0 * 20000.0 / (2.0 * n), 0.01);
  EXPECT_NEAR(p.z, -31.32, 0.01);
  // The chord's east component is N·sin(d/N): 32.7 mm short of the 20 km arc.
  EXPECT_NEAR(p.x, n * std::sin(20000.0 / n), 0.005);
  EXPECT_NEAR(p.x, 19999.967, 0.005);
  EXPECT_NEAR(p.y, 0.0, 1.5);  // the geodesic bends south of the parallel (~0.9 m)
}

TEST(LocalFrame, UpTiltsOneMilliradianPerSixKilometres) {
  const LocalFrame frame(kZion);
  const glm::dvec3 up = frame.upAt(test::travel(kZion, 0.0, 6371.0, 1200.0));
  EXPECT_NEAR(glm::length(up), 1.0, 1e-9);
  // Tilted towards +y (north) by ~1 mrad: the normal at the far point leans away from origin.
  EXPECT_NEAR(std::acos(up.z), 1.0e-3, 0.01e-3);
  EXPECT_GT(up.y, 0.0);
}

TEST(LocalFrame, RoundTripBelowAMillimetre) {
  const LocalFrame frame(kZion);
  double worst = 0.0;
  for (double az = 0.0; az < 360.0; az += 30.0) {
    for (double d : {10.0, 1000.0, 25000.0, 100000.0}) {
      for (double h : {-400.0, 1200.0, 4000.0}) {
        const Geodetic p = test::travel(kZion, az, d, h);
        worst = std::max(worst, test::metresBetween(p, frame.toGeodetic(frame.toLocal(p))));
      }
    }
  }
  EXPECT_LT(worst, 1e-3);
  EXPECT_LT(worst, 1e-6);  // in fact nanometres
}

TEST(LocalFrame, FrameAtCentreOfExtent) {
  const LocalFrame frame = frameAtCentre(GeoBounds{-113.2, 37.1, -112.8, 37.4}, 1500.0);
  EXPECT_NEAR(frame.origin().lonDeg, -113.0, 1e-12);
  EXPECT_NEAR(frame.origin().latDeg, 37.25, 1e-12);
  EXPECT_NEAR(frame.origin().heightM, 1500.0, 0.0);
  // Across the antimeridian the centre is on the short side.
  const LocalFrame fiji = frameAtCentre(GeoBounds{177.0, -19.0, -178.0, -16.0}, 0.0);
  EXPECT_NEAR(fiji.origin().lonDeg, 179.5, 1e-12);
  // Copies behave like the original.
  const LocalFrame copy = frame;
  const glm::dvec3 a = frame.toLocal(kZion);
  const glm::dvec3 b = copy.toLocal(kZion);
  EXPECT_NEAR(glm::length(a - b), 0.0, 1e-12);
}

}  // namespace
}  // namespace vegstream::geo
