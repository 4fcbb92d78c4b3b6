// Templates placed over a dataset's extent give valid paths inside it (the benchmark with the
// seed's §4 altitude profile), and the bundled Zion paths parse and stay over Zion.

#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>

#include "flight/flight_path_json.h"
#include "flight/path_sampler.h"
#include "flight/path_templates.h"

namespace vegstream::flight {
namespace {

const geo::GeoBounds kZion{-113.2396, 37.1321, -112.8521, 37.5129};
const GroundHeight kBumpy = [](double lat, double lon) {
  return 1500.0 + 400.0 * std::sin(lat * 300.0) * std::cos(lon * 250.0);
};

// Height above the ground at t, and the sampled pose.
double aboveGround(const PathSampler& s, double t, const GroundHeight& ground) {
  const FlightSample x = s.sample(t, ground);
  return x.position.heightM - ground(x.position.latDeg, x.position.lonDeg);
}

void expectBenchmarkProfile(const FlightPath& p, const GroundHeight& ground) {
  const PathSampler s(p);
  EXPECT_DOUBLE_EQ(s.duration(), 30.0);
  EXPECT_GE(aboveGround(s, 0.0, ground), 1500.0);
  EXPECT_LE(aboveGround(s, 0.0, ground), 2000.0);
  for (double t = 10.0; t <= 20.0; t += 0.25) {
    EXPECT_LE(aboveGround(s, t, ground), 25.0) << "t=" << t;
    EXPECT_GE(aboveGround(s, t, ground), kMinGroundClearanceM) << "t=" << t;
  }
  EXPECT_GT(aboveGround(s, 25.0, ground), 100.0) << "climbing after 20 s";
  EXPECT_GE(aboveGround(s, 30.0, ground), 1500.0);
}

TEST(PathTemplates, EachTemplateIsValidAndInsideItsDataset) {
  const geo::GeoBounds small{10.0, 45.0, 10.05, 45.03};  // ~4 × 3.3 km: templates scale down
  for (const geo::GeoBounds& b : {kZion, small}) {
    for (const std::string& name : templateNames()) {
      const Result<FlightPath> p = makePathFromTemplate(name, b, kBumpy);
      ASSERT_TRUE(p.ok()) << name << ": " << p.error().message;
      EXPECT_EQ(p->name, name);
      EXPECT_FALSE(findProblem(*p).has_value());
      EXPECT_TRUE(checkInside(*p, b).ok()) << name;
      // Round trip through JSON.
      const Result<FlightPath> again = parseFlightPath(flightPathToJson(*p), name + ".json");
      ASSERT_TRUE(again.ok()) << again.error().message;
      EXPECT_EQ(again->keyframes.size(), p->keyframes.size());
    }
  }
}

TEST(PathTemplates, BenchmarkFollowsTheSeedProfile) {
  const Result<FlightPath> p = makePathFromTemplate("benchmark-30s", kZion, kBumpy);
  ASSERT_TRUE(p.ok());
  expectBenchmarkProfile(*p, kBumpy);
  // Slow enough near the ground to see single plants: under 60 m/s between 11 and 19 s.
  const PathSampler s(*p);
  for (double t = 11.0; t <= 19.0; t += 0.5) {
    const glm::dvec3 v = s.sample(t, kBumpy).velocity;
    EXPECT_LT(std::hypot(v.x, v.y), 60.0) << "t=" << t;
  }
}

TEST(PathTemplates, OrbitCirclesOnePointAtOneHeight) {
  const Result<FlightPath> p = makePathFromTemplate("orbit", kZion, kBumpy);
  ASSERT_TRUE(p.ok());
  EXPECT_DOUBLE_EQ(p->duration(), 120.0);
  const PathSampler s(*p);
  const geo::LocalFrame centre({kZion.centre().y, kZion.centre().x, 0.0});
  double rMin = INFINITY, rMax = 0.0;
  for (int i = 0; i <= 240; ++i) {
    const FlightSample x = s.sample(i * 0.5, kBumpy);
    const glm::dvec3 l = centre.toLocal({x.position.latDeg, x.position.lonDeg, 0.0});
    rMin = std::min(rMin, std::hypot(l.x, l.y));
    rMax = std::max(rMax, std::hypot(l.x, l.y));
    EXPECT_NEAR(x.position.heightM, p->keyframes[0].altM, 1e-6) << "one MSL height";
    // Looks at the centre: the heading points from the camera to the centre.
    const double toCentre = std::atan2(-l.x, -l.y) * 180.0 / M_PI;
    EXPECT_NEAR(headingDelta(x.headingDeg, toCentre), 0.0, 2.0);
  }
  EXPECT_LT((rMax - rMin) / rMax, 0.01) << "a circle";
}

TEST(PathTemplates, UnknownTemplateListsTheKnownOnes) {
  const Result<FlightPath> p = makePathFromTemplate("benchmark", kZion, kBumpy);
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(p.error().kind, ErrorKind::InvalidInput);
  EXPECT_NE(p.error().message.find("known: benchmark-30s, canyon-run, orbit"), std::string::npos) << p.error().message;
}

TEST(BundledPaths, ParseAndStayOverZion) {
  const std::filesystem::path dir = VEGSTREAM_FLIGHT_PATHS_DIR;
  for (const char* name : {"benchmark-30s", "benchmark-30s-slickrock", "canyon-run", "orbit", "meadow-wind"}) {
    const Result<FlightPath> p = loadFlightPath(dir / (std::string(name) + ".json"));
    ASSERT_TRUE(p.ok()) << p.error().message;
    EXPECT_EQ(p->name, name);
    const Status inside = checkInside(*p, kZion);
    EXPECT_TRUE(inside.ok()) << (inside.ok() ? "" : inside.error().message);
  }
  for (const char* name : {"benchmark-30s", "benchmark-30s-slickrock"}) {
    const Result<FlightPath> bench = loadFlightPath(dir / (std::string(name) + ".json"));
    ASSERT_TRUE(bench.ok());
    expectBenchmarkProfile(*bench, kBumpy);
  }
  // The canyon run is long and fast.
  const Result<FlightPath> canyon = loadFlightPath(dir / "canyon-run.json");
  ASSERT_TRUE(canyon.ok());
  EXPECT_GE(canyon->duration(), 60.0);
  // The simulation's demo (issue 19): a vehicle, a rotor and gusts over the Kolob meadow; the
  // camera comes back along the trail after the vehicle has gone.
  const Result<FlightPath> meadow = loadFlightPath(dir / "meadow-wind.json");
  ASSERT_TRUE(meadow.ok());
  ASSERT_EQ(meadow->colliders.size(), 1u);
  ASSERT_TRUE(meadow->wind.has_value());
  EXPECT_EQ(meadow->wind->speedMps, 5.0);
  ASSERT_EQ(meadow->wind->sources.size(), 1u);
  EXPECT_EQ(meadow->wind->sources[0].type, WindSourceSpec::Type::Rotor);
  EXPECT_GT(meadow->duration(), meadow->colliders[0].keyframes.back().t + 20.0);
  // The trees' flight (issue 20): starts above the canopy, flies low along the forest edge, in wind.
  const Result<FlightPath> forest = loadFlightPath(dir / "kolob-forest.json");
  ASSERT_TRUE(forest.ok()) << forest.error().message;
  EXPECT_TRUE(checkInside(*forest, kZion).ok());
  ASSERT_TRUE(forest->wind.has_value());
  EXPECT_GE(forest->keyframes.front().altM, 50.0);
  double lowest = 1e9;
  for (const auto& k : forest->keyframes) lowest = std::min(lowest, k.altM);
  EXPECT_LE(lowest, 8.0);
}

}  // namespace
}  // namespace vegstream::flight
