// Camera poses along a flight path: through every keyframe at its time, C¹ in time, heading
// through ±180° without a flip, never below (or closer than 2 m to) the ground.

#include <cmath>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "flight/path_sampler.h"

namespace vegstream::flight {
namespace {

Keyframe kf(double t, double lat, double lon, double alt, AltRef ref, double heading = 0.0, double pitch = 0.0) {
  return Keyframe{t, lat, lon, alt, ref, heading, pitch};
}

// Unevenly spaced in time and distance, with a sharp turn, at MSL heights over flat ground.
FlightPath unevenPath() {
  FlightPath p;
  p.name = "uneven";
  p.keyframes = {
      kf(0, 37.20, -112.98, 2000, AltRef::Msl, 10, -10),       kf(3, 37.21, -112.97, 1900, AltRef::Msl, 20, -12),
      kf(4, 37.2105, -112.9690, 1850, AltRef::Msl, 80, -5),    kf(15, 37.25, -112.90, 1700, AltRef::Msl, 100, -30),
      kf(16, 37.2490, -112.8995, 1710, AltRef::Msl, 170, -20), kf(30, 37.20, -112.90, 2100, AltRef::Msl, 200, 0)};
  return p;
}

const GroundHeight kFlat = [](double, double) { return 1000.0; };

TEST(PathSampler, PassesThroughEveryKeyframeAtItsTime) {
  const FlightPath p = unevenPath();
  const PathSampler s(p);
  EXPECT_DOUBLE_EQ(s.duration(), 30.0);
  for (const Keyframe& k : p.keyframes) {
    const FlightSample x = s.sample(k.t, kFlat);
    EXPECT_NEAR(x.position.latDeg, k.lat, 1e-9) << "t=" << k.t;  // 0.1 mm
    EXPECT_NEAR(x.position.lonDeg, k.lon, 1e-9) << "t=" << k.t;
    EXPECT_NEAR(x.position.heightM, k.altM, 1e-6) << "t=" << k.t;
    EXPECT_NEAR(headingDelta(x.headingDeg, k.headingDeg), 0.0, 1e-9);
    EXPECT_NEAR(x.pitchDeg, k.pitchDeg, 1e-9);
  }
  // A terrain-relative keyframe lands at ground + alt.
  FlightPath q = p;
  q.keyframes[2].altRef = AltRef::Terrain;
  q.keyframes[2].altM = 50.0;
  EXPECT_NEAR(sampleAt(q, 4.0, kFlat).position.heightM, 1050.0, 1e-6);
}

TEST(PathSampler, VelocityIsContinuousAcrossKeyframes) {
  const FlightPath p = unevenPath();
  const PathSampler s(p);
  const geo::LocalFrame& f = s.frame();
  auto at = [&](double t) { return f.toLocal(s.sample(t, kFlat).position); };
  const double h = 1e-4;
  for (std::size_t i = 1; i + 1 < p.keyframes.size(); ++i) {
    const double t = p.keyframes[i].t;
    const glm::dvec3 left = (at(t) - at(t - h)) / h;
    const glm::dvec3 right = (at(t + h) - at(t)) / h;
    const double speed = glm::length(left);
    EXPECT_GT(speed, 1.0) << "keyframe " << i;
    EXPECT_LT(glm::length(left - right), 0.01 * speed + 0.05) << "keyframe " << i << ": " << speed << " m/s";
    // The sample's own velocity agrees.
    EXPECT_LT(glm::length(s.sample(t, kFlat).velocity - left), 0.01 * speed + 0.05);
  }
}

TEST(PathSampler, HeadingCrossesSouthWithoutFlipping) {
  FlightPath p;
  p.keyframes = {kf(0, 37.2, -113.0, 100, AltRef::Terrain, 170, 0),
                 kf(10, 37.21, -113.0, 100, AltRef::Terrain, -170, 0),
                 kf(20, 37.22, -113.0, 100, AltRef::Terrain, 160, 0)};
  const PathSampler s(p);
  // Unwrapped, the keyframes are 170 → 190 → 160: every sample stays within 20° of south
  // (never near 0°/north) and the heading crosses 180° on the way.
  double previous = s.sample(0.0, kFlat).headingDeg, turned = 0.0, maxStep = 0.0;
  bool crossedSouth = false;
  for (int i = 1; i <= 2000; ++i) {
    const double h = s.sample(20.0 * i / 2000.0, kFlat).headingDeg;
    EXPECT_GE(h, 0.0);
    EXPECT_LT(h, 360.0);
    EXPECT_LE(std::abs(headingDelta(180.0, h)), 20.0 + 1e-9) << "t=" << 20.0 * i / 2000.0 << " heading " << h;
    if (previous < 180.0 && h >= 180.0) crossedSouth = true;
    const double d = headingDelta(previous, h);
    maxStep = std::max(maxStep, std::abs(d));
    if (i <= 1000) turned += d;
    previous = h;
  }
  EXPECT_TRUE(crossedSouth);
  EXPECT_LT(maxStep, 0.1) << "no jump between samples 10 ms apart";
  EXPECT_NEAR(turned, 20.0, 1e-6) << "turned 20° clockwise in the first 10 s";
}

TEST(PathSampler, NeverBelowBumpyGround) {
  // Ridges up to ±300 m at ~1 km wavelength under a path that asks for 0–30 m above the
  // terrain and, once, for an MSL height below the ground.
  const GroundHeight bumpy = [](double lat, double lon) {
    return 1500.0 + 300.0 * std::sin(lat * 700.0) * std::cos(lon * 900.0) + 40.0 * std::sin(lat * 5000.0);
  };
  FlightPath p;
  p.keyframes = {kf(0, 37.20, -113.00, 30, AltRef::Terrain), kf(8, 37.23, -112.98, 0, AltRef::Terrain),
                 kf(12, 37.24, -112.95, 1200, AltRef::Msl), kf(20, 37.26, -112.93, 5, AltRef::Terrain)};
  const PathSampler s(p);
  double lowest = INFINITY;
  for (int i = 0; i < 1000; ++i) {
    const FlightSample x = s.sample(20.0 * i / 999.0, bumpy);
    const double clearance = x.position.heightM - bumpy(x.position.latDeg, x.position.lonDeg);
    lowest = std::min(lowest, clearance);
    EXPECT_NEAR(x.heightAboveGroundM, clearance, 1e-9);
  }
  EXPECT_GE(lowest, kMinGroundClearanceM - 1e-9);
  EXPECT_LT(lowest, kMinGroundClearanceM + 1e-6) << "the clearance floor was exercised";
  // Unknown ground (NaN) counts as sea level.
  const FlightSample x = s.sample(0.0, [](double, double) { return NAN; });
  EXPECT_NEAR(x.position.heightM, 30.0, 1e-6);
}

TEST(PathSampler, ForwardVectorIsEnu) {
  EXPECT_LT(glm::length(forwardVector(0, 0) - glm::dvec3(0, 1, 0)), 1e-12);
  EXPECT_LT(glm::length(forwardVector(90, 0) - glm::dvec3(1, 0, 0)), 1e-12);
  EXPECT_LT(glm::length(forwardVector(180, -90) - glm::dvec3(0, 0, -1)), 1e-12);
  const glm::dvec3 f = forwardVector(45, -30);
  EXPECT_NEAR(glm::length(f), 1.0, 1e-12);
  EXPECT_NEAR(f.z, -0.5, 1e-12);
  EXPECT_NEAR(f.x, f.y, 1e-12);
  EXPECT_DOUBLE_EQ(headingDelta(170, -170), 20.0);
  EXPECT_DOUBLE_EQ(headingDelta(-170, 170), -20.0);
  EXPECT_DOUBLE_EQ(headingDelta(0, 180), 180.0);
}

TEST(PathSampler, CollidersFollowTheirKeyframes) {
  FlightPath p = unevenPath();
  Collider ball{"ball",
                Collider::Shape::Sphere,
                1.5,
                0.0,
                {{0, 37.20, -112.98, 1.5, AltRef::Terrain}, {10, 37.201, -112.98, 1.5, AltRef::Terrain}}};
  Collider post{"post", Collider::Shape::Capsule, 0.5, 4.0, {{0, 37.205, -112.975, 1100, AltRef::Msl}}};
  p.colliders = {ball, post};
  const PathSampler s(p);
  ASSERT_EQ(s.colliderCount(), 2u);
  const ColliderSample a = s.collider(0, 10.0, kFlat);
  EXPECT_NEAR(a.centre.latDeg, 37.201, 1e-9);
  EXPECT_NEAR(a.centre.heightM, 1001.5, 1e-6);
  EXPECT_NEAR(s.collider(0, 5.0, kFlat).centre.latDeg, 37.2005, 1e-6) << "two keyframes: a straight line";
  EXPECT_NEAR(s.collider(0, 25.0, kFlat).centre.latDeg, 37.201, 1e-9) << "held after its last keyframe";
  const ColliderSample b = s.collider(1, 7.0, kFlat);
  EXPECT_NEAR(b.centre.heightM, 1100.0, 1e-6);
  EXPECT_DOUBLE_EQ(b.lengthM, 4.0);
  EXPECT_DOUBLE_EQ(a.lengthM, 0.0);
}

// A wind source moves exactly as a collider with the same keyframes: one track, the same code.
TEST(PathSampler, WindSourcesMoveLikeColliders) {
  FlightPath p = unevenPath();
  const std::vector<ColliderKeyframe> keys = {{0, 37.20, -112.98, 5, AltRef::Terrain},
                                              {4, 37.203, -112.978, 1200, AltRef::Msl},
                                              {9, 37.204, -112.972, 20, AltRef::Terrain},
                                              {20, 37.210, -112.970, 20, AltRef::Terrain}};
  p.colliders = {Collider{"twin", Collider::Shape::Sphere, 1.0, 0.0, keys}};
  WindSection wind;
  wind.sources = {WindSourceSpec{"fan", WindSourceSpec::Type::Fan, 12.0, 9.0, 90.0, keys},
                  WindSourceSpec{"rotor", WindSourceSpec::Type::Rotor, 8.0, 14.0, std::nullopt,
                                 {{0, 37.205, -112.975, 1100, AltRef::Msl}}}};
  p.wind = wind;
  ASSERT_FALSE(findProblem(p).has_value());
  const PathSampler s(p);
  ASSERT_EQ(s.windSourceCount(), 2u);
  const GroundHeight bumpy = [](double lat, double lon) { return 1000.0 + 50.0 * std::sin(lat * 3000.0 + lon * 2000.0); };
  for (double t : {0.0, 1.3, 4.0, 6.5, 9.0, 14.2, 20.0, 30.0}) {
    SCOPED_TRACE(t);
    const WindSourceSample w = s.windSource(0, t, bumpy);
    const ColliderSample c = s.collider(0, t, bumpy);
    EXPECT_DOUBLE_EQ(w.centre.latDeg, c.centre.latDeg);
    EXPECT_DOUBLE_EQ(w.centre.lonDeg, c.centre.lonDeg);
    EXPECT_DOUBLE_EQ(w.centre.heightM, c.centre.heightM);
  }
  EXPECT_NEAR(s.windSource(0, 4.0, bumpy).centre.latDeg, 37.203, 1e-9) << "at its keyframe at its time";
  EXPECT_NEAR(s.windSource(0, 4.0, bumpy).centre.heightM, 1200.0, 1e-6) << "MSL keyframe";
  const WindSourceSample fan = s.windSource(0, 2.0, kFlat);
  EXPECT_EQ(fan.type, WindSourceSpec::Type::Fan);
  EXPECT_DOUBLE_EQ(fan.radiusM, 12.0);
  EXPECT_DOUBLE_EQ(fan.strengthMps, 9.0);
  EXPECT_DOUBLE_EQ(fan.directionDeg, 90.0);
  const WindSourceSample rotor = s.windSource(1, 7.0, kFlat);
  EXPECT_EQ(rotor.type, WindSourceSpec::Type::Rotor);
  EXPECT_DOUBLE_EQ(rotor.directionDeg, 0.0) << "no direction: 0";
  EXPECT_NEAR(rotor.centre.heightM, 1100.0, 1e-6) << "one keyframe: fixed";
  EXPECT_NEAR(rotor.centre.latDeg, 37.205, 1e-9);

  EXPECT_EQ(PathSampler(unevenPath()).windSourceCount(), 0u) << "no wind section: no sources";
}

}  // namespace
}  // namespace vegstream::flight
