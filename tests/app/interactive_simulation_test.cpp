// The window's simulation controls without a window (issue 19): the wind keys step and clamp
// the wind (wind_controls.h), the HUD's sliders change it and nothing else does, and the camera's
// collider (camera_collider.h) cycles off → walking → driving and stands on the ground ahead of
// the camera along its heading.

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "app/camera_collider.h"
#include "app/hud.h"
#include "app/imgui_overlay.h"
#include "app/wind_controls.h"

namespace vegstream::app {
namespace {

simulation::WindOptions wind(double speed, double direction, double gustiness) {
  simulation::WindOptions w;
  w.speedMps = speed;
  w.directionDeg = direction;
  w.gustiness = gustiness;
  return w;
}

WindKeys keys(int speed, int direction, int gustiness, bool coarse = false) {
  WindKeys k;
  k.speedSteps = speed;
  k.directionSteps = direction;
  k.gustinessSteps = gustiness;
  k.coarse = coarse;
  return k;
}

TEST(WindControls, SpeedStepsByOneMetrePerSecondWithinZeroToHundred) {
  EXPECT_DOUBLE_EQ(stepWind(wind(10, 0, 0.5), keys(1, 0, 0)).speedMps, 11.0);
  EXPECT_DOUBLE_EQ(stepWind(wind(10, 0, 0.5), keys(-1, 0, 0)).speedMps, 9.0);
  EXPECT_DOUBLE_EQ(stepWind(wind(0, 0, 0.5), keys(-1, 0, 0)).speedMps, 0.0);
  EXPECT_DOUBLE_EQ(stepWind(wind(99.5, 0, 0.5), keys(1, 0, 0)).speedMps, 100.0);
  EXPECT_DOUBLE_EQ(stepWind(wind(100, 0, 0.5), keys(1, 0, 0)).speedMps, 100.0);
  // Shift: 10 m/s a press, still clamped.
  EXPECT_DOUBLE_EQ(stepWind(wind(5, 0, 0.5), keys(1, 0, 0, true)).speedMps, 15.0);
  EXPECT_DOUBLE_EQ(stepWind(wind(95, 0, 0.5), keys(1, 0, 0, true)).speedMps, 100.0);
  EXPECT_DOUBLE_EQ(stepWind(wind(5, 0, 0.5), keys(-1, 0, 0, true)).speedMps, 0.0);
  // A press changes only its own value.
  const simulation::WindOptions w = stepWind(wind(10, 270, 0.3), keys(1, 0, 0));
  EXPECT_DOUBLE_EQ(w.directionDeg, 270.0);
  EXPECT_DOUBLE_EQ(w.gustiness, 0.3);
}

TEST(WindControls, DirectionTurnsByFifteenDegreesWrappedIntoZeroTo360) {
  EXPECT_DOUBLE_EQ(stepWind(wind(5, 90, 0.5), keys(0, 1, 0)).directionDeg, 105.0);
  EXPECT_DOUBLE_EQ(stepWind(wind(5, 90, 0.5), keys(0, -1, 0)).directionDeg, 75.0);
  EXPECT_DOUBLE_EQ(stepWind(wind(5, 350, 0.5), keys(0, 1, 0)).directionDeg, 5.0);
  EXPECT_DOUBLE_EQ(stepWind(wind(5, 0, 0.5), keys(0, -1, 0)).directionDeg, 345.0);
  EXPECT_DOUBLE_EQ(stepWind(wind(5, 345, 0.5), keys(0, 1, 0)).directionDeg, 0.0);
  EXPECT_DOUBLE_EQ(stepWind(wind(5, -90, 0.5), keys(0, 1, 0)).directionDeg, 285.0);  // a command line's −90
  EXPECT_DOUBLE_EQ(stepWind(wind(5, 725, 0.5), keys(0, 1, 0)).directionDeg, 20.0);
  // 24 presses: a full turn, back where it started.
  simulation::WindOptions w = wind(5, 30, 0.5);
  for (int i = 0; i < 24; ++i) w = stepWind(w, keys(0, 1, 0));
  EXPECT_DOUBLE_EQ(w.directionDeg, 30.0);
}

TEST(WindControls, GustinessStepsByATenthWithinZeroToOneWithoutDrift) {
  simulation::WindOptions w = wind(5, 0, 0.0);
  for (int i = 0; i < 3; ++i) w = stepWind(w, keys(0, 0, 1));
  EXPECT_EQ(w.gustiness, 0.3);  // exactly: kept to hundredths
  for (int i = 0; i < 20; ++i) w = stepWind(w, keys(0, 0, 1));
  EXPECT_EQ(w.gustiness, 1.0);
  for (int i = 0; i < 25; ++i) w = stepWind(w, keys(0, 0, -1));
  EXPECT_EQ(w.gustiness, 0.0);
  EXPECT_DOUBLE_EQ(stepWind(wind(5, 0, 0.55), keys(0, 0, 1)).gustiness, 0.65);
}

TEST(WindControls, ClampKeepsSliderValuesInRange) {
  const simulation::WindOptions w = clampWind(wind(120, 400, 1.2));
  EXPECT_DOUBLE_EQ(w.speedMps, 100.0);
  EXPECT_DOUBLE_EQ(w.directionDeg, 400.0);  // any direction is valid
  EXPECT_DOUBLE_EQ(w.gustiness, 1.0);
  const simulation::WindOptions n = clampWind(wind(NAN, NAN, -0.5));
  EXPECT_DOUBLE_EQ(n.speedMps, 0.0);
  EXPECT_DOUBLE_EQ(n.directionDeg, 0.0);
  EXPECT_DOUBLE_EQ(n.gustiness, 0.0);
  EXPECT_FALSE(keys(0, 0, 0).any());
  EXPECT_TRUE(keys(0, -1, 0).any());
}

TEST(WindControls, HudLineNamesSpeedFromDirectionAndGusts) {
  EXPECT_EQ(describeWind(wind(12, 270, 0.5)), "12.0 m/s from 270\xC2\xB0 (W), gusts 0.50");
  EXPECT_EQ(describeWind(wind(0.5, -45, 0)), "0.5 m/s from 315\xC2\xB0 (NW), gusts 0.00");
  EXPECT_STREQ(compassPoint(0), "N");
  EXPECT_STREQ(compassPoint(22.4), "N");
  EXPECT_STREQ(compassPoint(22.6), "NE");
  EXPECT_STREQ(compassPoint(90), "E");
  EXPECT_STREQ(compassPoint(180), "S");
  EXPECT_STREQ(compassPoint(359), "N");
}

// The sliders: clicks over the whole HUD find a slider for each value; every edit is within the
// limits and changes one value; without a pointer (the right button turning the camera) a
// pressed button changes nothing.
TEST(WindControls, HudSlidersChangeTheWind) {
  ImGuiOverlay overlay;
  HudState s;
  s.datasetName = "test";
  s.deviceName = "llvmpipe";
  s.wind = wind(50, 180, 0.5);
  auto frame = [&](const OverlayPointer& p) {
    overlay.begin(1280.0f, 900.0f, 1.0 / 60.0, p);
    const HudEdits e = drawHud(s);
    overlay.end();
    return e;
  };
  frame({});
  frame({});  // ImGui sizes auto-resizing windows on the second frame
  OverlayPointer captured{false, 100.0f, 100.0f, true};
  for (int i = 0; i < 3; ++i) EXPECT_FALSE(frame(captured).wind);
  bool speed = false, direction = false, gustiness = false;
  for (float y = 0.0f; y < 900.0f; y += 4.0f)
    for (float x = 20.0f; x < 200.0f; x += 40.0f) {
      EXPECT_FALSE(frame({true, x, y, false}).wind);  // hovering changes nothing
      const HudEdits e = frame({true, x, y, true});
      frame({true, x, y, false});
      if (!e.wind) continue;
      const simulation::WindOptions& w = *e.wind;
      EXPECT_GE(w.speedMps, 0.0);
      EXPECT_LE(w.speedMps, 100.0);
      EXPECT_GE(w.directionDeg, 0.0);
      EXPECT_LE(w.directionDeg, 360.0);
      EXPECT_GE(w.gustiness, 0.0);
      EXPECT_LE(w.gustiness, 1.0);
      const int changed = (w.speedMps != 50.0) + (w.directionDeg != 180.0) + (w.gustiness != 0.5);
      EXPECT_EQ(changed, 1) << x << ", " << y;
      speed |= w.speedMps != 50.0;
      direction |= w.directionDeg != 180.0;
      gustiness |= w.gustiness != 0.5;
    }
  EXPECT_TRUE(speed);
  EXPECT_TRUE(direction);
  EXPECT_TRUE(gustiness);
  // With the simulation off there is nothing to set.
  s.simulationOn = false;
  for (float y = 0.0f; y < 900.0f; y += 4.0f) {
    frame({true, 60.0f, y, true});
    EXPECT_FALSE(frame({true, 60.0f, y, false}).wind);
  }
}

// The camera's collider.
const geo::LocalFrame kFrame({37.25, -112.95, 0.0});

// Ground rising northwards and eastwards (metres MSL).
double slopedGround(double latDeg, double lonDeg) {
  return 1500.0 + (latDeg - 37.25) * 20'000.0 + (lonDeg + 112.95) * 5'000.0;
}

TEST(CameraCollider, CKeyCyclesOffWalkingDrivingOff) {
  CameraColliderMode m = CameraColliderMode::Off;
  EXPECT_STREQ(cameraColliderName(m), "off");
  m = nextCameraColliderMode(m);
  EXPECT_EQ(m, CameraColliderMode::Walking);
  EXPECT_STREQ(cameraColliderName(m), "walking");
  m = nextCameraColliderMode(m);
  EXPECT_EQ(m, CameraColliderMode::Driving);
  EXPECT_STREQ(cameraColliderName(m), "driving");
  EXPECT_EQ(nextCameraColliderMode(m), CameraColliderMode::Off);
  const CameraColliderShape walk = cameraColliderShape(CameraColliderMode::Walking);
  EXPECT_DOUBLE_EQ(walk.radiusM, 0.35);
  EXPECT_DOUBLE_EQ(walk.lengthM, 1.1);
  EXPECT_DOUBLE_EQ(walk.aheadM, 1.5);
  const CameraColliderShape drive = cameraColliderShape(CameraColliderMode::Driving);
  EXPECT_DOUBLE_EQ(drive.radiusM, 1.2);
  EXPECT_DOUBLE_EQ(drive.lengthM, 0.5);
  EXPECT_DOUBLE_EQ(drive.aheadM, 3.0);
}

// Placed ahead of the camera's ground point along the heading in the frame's horizontal plane
// (the fly camera's), its bottom on the ground there — also 400 m up and 20 km from the frame's
// origin, where the frame's up tilts by 3 mrad from the local vertical.
TEST(CameraCollider, StandsOnTheGroundAheadAlongTheHeading) {
  for (const CameraColliderMode mode : {CameraColliderMode::Walking, CameraColliderMode::Driving}) {
    const CameraColliderShape shape = cameraColliderShape(mode);
    for (const glm::dvec3 offset : {glm::dvec3(0.0), glm::dvec3(15'000.0, 13'000.0, 0.0)})
      for (const double agl : {1.7, 400.0})
        for (const double heading : {0.0, 45.0, 90.0, 200.0, 315.0}) {
          geo::Geodetic cam = kFrame.toGeodetic(offset);
          cam.heightM = slopedGround(cam.latDeg, cam.lonDeg) + agl;
          const auto c = cameraCollider(mode, kFrame, slopedGround, cam, heading);
          ASSERT_TRUE(c);
          const glm::dvec3 foot = kFrame.toLocal({cam.latDeg, cam.lonDeg, slopedGround(cam.latDeg, cam.lonDeg)});
          const glm::dvec3 at = kFrame.toLocal(c->centre);
          const double h = heading * M_PI / 180.0;
          EXPECT_NEAR(at.x - foot.x, std::sin(h) * shape.aheadM, 0.01) << heading << " " << agl;
          EXPECT_NEAR(at.y - foot.y, std::cos(h) * shape.aheadM, 0.01) << heading << " " << agl;
          EXPECT_DOUBLE_EQ(c->centre.heightM,
                           slopedGround(c->centre.latDeg, c->centre.lonDeg) + shape.radiusM + 0.5 * shape.lengthM);
          EXPECT_DOUBLE_EQ(c->radiusM, shape.radiusM);
          EXPECT_DOUBLE_EQ(c->lengthM, shape.lengthM);
        }
  }
}

TEST(CameraCollider, NoneWhenOffOrWhereTheGroundIsUnknown) {
  const geo::Geodetic cam{37.25, -112.95, 2000.0};
  EXPECT_FALSE(cameraCollider(CameraColliderMode::Off, kFrame, slopedGround, cam, 0.0));
  const flight::GroundHeight none = [](double, double) { return NAN; };
  EXPECT_FALSE(cameraCollider(CameraColliderMode::Walking, kFrame, none, cam, 0.0));
  EXPECT_FALSE(cameraCollider(CameraColliderMode::Walking, kFrame, flight::GroundHeight{}, cam, 0.0));
}

}  // namespace
}  // namespace vegstream::app
