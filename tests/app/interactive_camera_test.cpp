// The interactive fly camera's maths, driven by plain input numbers (no window): WASD/QE move
// along the heading in the scene's ENU frame, mouse-look clamps pitch to ±89°, the wheel and
// Shift scale the speed, follow-terrain holds the height above the ground, and the camera
// never goes below ground + 2 m.

#include <cmath>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "app/fly_camera.h"

namespace vegstream::app {
namespace {

const geo::LocalFrame kFrame({37.25, -112.95, 0.0});

// Ground rising 1 m per ~10 m northwards (0.1° of latitude ≈ 11 km → 1100 m).
double rampGround(double latDeg, double /*lonDeg*/) { return 1000.0 + (latDeg - 37.25) * 10'000.0; }

FlyCamera cameraAt(double agl, double heading, double pitch, FlyCameraSettings settings = {}) {
  const geo::Geodetic g{37.25, -112.95, rampGround(37.25, -112.95) + agl};
  return FlyCamera(kFrame, rampGround, kFrame.toLocal(g), heading, pitch, settings);
}

TEST(InteractiveCamera, ForwardMovesAlongTheHeadingInEnu) {
  for (double heading : {0.0, 45.0, 90.0, 200.0, 315.0}) {
    FlyCamera cam = cameraAt(500.0, heading, 0.0);
    const glm::dvec3 before = cam.position();
    FlyInput in;
    in.forward = 1.0;
    cam.update(in, 0.5);
    const glm::dvec3 d = cam.position() - before;
    const double h = heading * M_PI / 180.0;
    EXPECT_NEAR(d.x, std::sin(h) * 80.0 * 0.5, 1e-6) << heading;  // east
    EXPECT_NEAR(d.y, std::cos(h) * 80.0 * 0.5, 1e-6) << heading;  // north
    EXPECT_NEAR(d.z, 0.0, 1e-9) << heading;
  }
}

TEST(InteractiveCamera, StrafeBackAndVertical) {
  FlyCamera cam = cameraAt(500.0, 0.0, 0.0);
  glm::dvec3 p = cam.position();
  FlyInput right;
  right.right = 1.0;  // D: east when facing north
  cam.update(right, 1.0);
  EXPECT_NEAR(cam.position().x - p.x, 80.0, 1e-6);
  EXPECT_NEAR(cam.position().y - p.y, 0.0, 1e-6);
  p = cam.position();
  FlyInput back;
  back.forward = -1.0;  // S
  cam.update(back, 1.0);
  EXPECT_NEAR(cam.position().y - p.y, -80.0, 1e-6);
  p = cam.position();
  FlyInput up;
  up.up = 1.0;  // E
  cam.update(up, 1.0);
  EXPECT_NEAR(cam.position().z - p.z, 80.0, 1e-6);
}

TEST(InteractiveCamera, ForwardFollowsPitchAndDiagonalsAreNotFaster) {
  FlyCamera cam = cameraAt(2000.0, 90.0, -30.0);
  const glm::dvec3 before = cam.position();
  FlyInput in;
  in.forward = 1.0;
  in.right = 1.0;
  cam.update(in, 1.0);
  EXPECT_NEAR(glm::length(cam.position() - before), 80.0, 1e-6);
  EXPECT_LT(cam.position().z, before.z);  // looking down: W descends
}

TEST(InteractiveCamera, MouseLookClampsPitchAndWrapsHeading) {
  FlyCamera cam = cameraAt(500.0, 350.0, 0.0);
  FlyInput in;
  in.lookDyPx = -100'000.0;  // mouse far up
  cam.update(in, 0.016);
  EXPECT_DOUBLE_EQ(cam.pitchDeg(), 89.0);
  in.lookDyPx = 100'000.0;
  cam.update(in, 0.016);
  EXPECT_DOUBLE_EQ(cam.pitchDeg(), -89.0);
  FlyInput turn;
  turn.lookDxPx = 100.0;  // 15° right: 350 → 5
  cam.update(turn, 0.016);
  EXPECT_NEAR(cam.headingDeg(), 5.0, 1e-9);
  turn.lookDxPx = -200.0;  // 30° left: 5 → 335
  cam.update(turn, 0.016);
  EXPECT_NEAR(cam.headingDeg(), 335.0, 1e-9);
}

TEST(InteractiveCamera, WheelAndShiftScaleTheSpeed) {
  FlyCameraSettings settings;
  settings.speedMps = 100.0;
  FlyCamera cam = cameraAt(500.0, 0.0, 0.0, settings);
  FlyInput wheel;
  wheel.wheelSteps = 2.0;
  cam.update(wheel, 0.0);
  EXPECT_NEAR(cam.speedMps(), 156.25, 1e-9);
  wheel.wheelSteps = -1000.0;
  cam.update(wheel, 0.0);
  EXPECT_DOUBLE_EQ(cam.speedMps(), settings.minSpeedMps);
  wheel.wheelSteps = 1000.0;
  cam.update(wheel, 0.0);
  EXPECT_DOUBLE_EQ(cam.speedMps(), settings.maxSpeedMps);

  FlyCamera slow = cameraAt(500.0, 0.0, 0.0, settings), fast = cameraAt(500.0, 0.0, 0.0, settings);
  FlyInput in;
  in.forward = 1.0;
  const glm::dvec3 p0 = slow.position();
  slow.update(in, 1.0);
  in.fast = true;
  fast.update(in, 1.0);
  EXPECT_NEAR(glm::length(fast.position() - p0), 5.0 * glm::length(slow.position() - p0), 1e-6);
}

TEST(InteractiveCamera, FollowTerrainKeepsTheHeightAboveGround) {
  FlyCamera cam = cameraAt(120.0, 0.0, 10.0);  // heading north, up the ramp, looking up
  cam.setFollowTerrain(true);
  EXPECT_NEAR(cam.followHeightM(), 120.0, 1e-3);
  FlyInput in;
  in.forward = 1.0;
  for (int i = 0; i < 100; ++i) {
    cam.update(in, 0.1);
    ASSERT_NEAR(cam.heightAboveGroundM(), 120.0, 1e-3) << i;
  }
  EXPECT_GT(cam.groundBelowM(), rampGround(37.25, 0.0) + 50.0) << "it climbed with the ground";
  // Q lowers the followed height, never below the clearance.
  FlyInput down;
  down.up = -1.0;
  for (int i = 0; i < 100; ++i) cam.update(down, 0.1);
  EXPECT_NEAR(cam.heightAboveGroundM(), flight::kMinGroundClearanceM, 1e-3);
  cam.setFollowTerrain(false);
  EXPECT_FALSE(cam.followTerrain());
}

TEST(InteractiveCamera, NeverBelowGroundPlusClearance) {
  FlyCamera low = cameraAt(-50.0, 0.0, 0.0);  // starts underground
  EXPECT_NEAR(low.heightAboveGroundM(), flight::kMinGroundClearanceM, 1e-3);

  FlyCamera cam = cameraAt(300.0, 180.0, -89.0);  // diving
  FlyInput in;
  in.forward = 1.0;
  in.up = -1.0;
  in.fast = true;
  for (int i = 0; i < 200; ++i) {
    cam.update(in, 0.05);
    ASSERT_GE(cam.heightAboveGroundM(), flight::kMinGroundClearanceM - 1e-6) << i;
  }
  EXPECT_NEAR(cam.heightAboveGroundM(), flight::kMinGroundClearanceM, 1e-3);
  const flight::FlightSample s = cam.sample();
  EXPECT_NEAR(s.heightAboveGroundM, flight::kMinGroundClearanceM, 1e-3);
  EXPECT_DOUBLE_EQ(s.pitchDeg, -89.0);
}

TEST(InteractiveCamera, UnknownGroundCountsAsSeaLevel) {
  auto nowhere = [](double, double) { return std::nan(""); };
  FlyCamera cam(kFrame, nowhere, kFrame.toLocal({37.25, -112.95, -100.0}), 0.0, 0.0);
  EXPECT_NEAR(cam.geodetic().heightM, flight::kMinGroundClearanceM, 1e-3);
}

}  // namespace
}  // namespace vegstream::app
