// The demo's straight flight: interpolates between its ends, keeps its height above the
// highest nearby ground, looks along the flight direction at its pitch.

#include <cmath>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "scene/straight_flight.h"

namespace vegstream::scene {
using namespace vegstream::flight;
namespace {

TEST(StraightFlight, FollowsTheLineAboveTheGround) {
  StraightFlight f;
  f.start = {37.20, -113.05, 0.0};
  f.end = {37.30, -112.95, 0.0};
  f.altitudeAboveTerrainM = 500.0;
  f.durationS = 10.0;
  f.pitchDeg = -10.0;
  const geo::LocalFrame frame({37.25, -113.0, 0.0});
  // A ridge at longitude −113.0 rises to 2500 m; elsewhere 1500 m.
  auto ground = [](double, double lon) { return std::abs(lon + 113.0) < 0.002 ? 2500.0 : 1500.0; };

  const FlightPose a = poseAt(f, 0.0, frame, ground);
  EXPECT_NEAR(a.position.latDeg, 37.20, 1e-12);
  EXPECT_NEAR(a.position.heightM, 2000.0, 1e-9);
  const FlightPose mid = poseAt(f, 5.0, frame, ground);
  EXPECT_NEAR(mid.position.lonDeg, -113.0, 1e-12);
  EXPECT_NEAR(mid.position.heightM, 3000.0, 1e-9) << "clears the ridge under it";
  const FlightPose past = poseAt(f, 99.0, frame, ground);
  EXPECT_NEAR(past.position.latDeg, 37.30, 1e-12) << "time is clamped to the path";

  // Looks north-east and 10° down.
  const glm::dvec3 fwd = mid.camera.forward;
  EXPECT_NEAR(glm::length(fwd), 1.0, 1e-12);
  EXPECT_GT(fwd.x, 0.0);
  EXPECT_GT(fwd.y, 0.0);
  EXPECT_NEAR(std::asin(glm::dot(fwd, mid.camera.up)), -10.0 * M_PI / 180.0, 1e-9);
  // The camera position is the geodetic position in the local frame.
  EXPECT_LT(glm::length(mid.camera.position - frame.toLocal(mid.position)), 1e-6);
}

TEST(StraightFlight, UnknownGroundCountsAsSeaLevel) {
  StraightFlight f;
  f.start = {10.0, 10.0, 0.0};
  f.end = {10.1, 10.0, 0.0};
  const geo::LocalFrame frame({10.05, 10.0, 0.0});
  const FlightPose p = poseAt(f, 1.0, frame, [](double, double) { return std::nan(""); });
  EXPECT_NEAR(p.position.heightM, f.altitudeAboveTerrainM, 1e-9);
}

}  // namespace
}  // namespace vegstream::scene
