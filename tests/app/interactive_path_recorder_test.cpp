// Recording a flown path (R in the window): keyframes every 0.5 s in time order, altitudes
// MSL, written atomically as flight JSON that flight::loadFlightPath accepts.

#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>

#include "app/path_recorder.h"
#include "flight/flight_path_json.h"
#include "tests/support/test_dirs.h"

namespace vegstream::app {
namespace {
namespace fs = std::filesystem;

flight::FlightSample poseAt(double t) {
  flight::FlightSample s;
  s.position = {37.2 + 1e-4 * t, -112.98 + 2e-4 * t, 1500.0 + 3.0 * t};
  s.headingDeg = std::fmod(350.0 + 4.0 * t, 360.0);  // crosses north
  s.pitchDeg = -10.0;
  return s;
}

TEST(InteractivePathRecorder, KeyframesEveryHalfSecondLoadableJson) {
  PathRecorder rec;
  const double t0 = 12.0;  // wall time when R was pressed
  rec.start(t0, poseAt(0.0));
  EXPECT_TRUE(rec.recording());
  for (double t = 0.016; t < 3.2; t += 0.016) rec.add(t0 + t, poseAt(t));
  auto path = rec.stop(t0 + 3.2, poseAt(3.2), "flown");
  ASSERT_TRUE(path) << path.error().message;
  EXPECT_FALSE(rec.recording());
  ASSERT_GE(path->keyframes.size(), 7u);
  EXPECT_LE(path->keyframes.size(), 8u);
  EXPECT_DOUBLE_EQ(path->keyframes.front().t, 0.0);
  EXPECT_NEAR(path->keyframes.back().t, 3.2, 1e-9);
  for (size_t i = 1; i < path->keyframes.size(); ++i) {
    EXPECT_GT(path->keyframes[i].t, path->keyframes[i - 1].t);
    if (i + 1 < path->keyframes.size()) {
      EXPECT_NEAR(path->keyframes[i].t - path->keyframes[i - 1].t, 0.5, 0.02);
    }
    EXPECT_EQ(path->keyframes[i].altRef, flight::AltRef::Msl);
  }

  const fs::path dir = vegstream::testing::testOutputDir();
  const fs::path file = dir / "flown.json";
  ASSERT_TRUE(saveFlightPath(*path, file));
  auto loaded = flight::loadFlightPath(file);
  ASSERT_TRUE(loaded) << loaded.error().message;
  ASSERT_EQ(loaded->keyframes.size(), path->keyframes.size());
  for (size_t i = 0; i < loaded->keyframes.size(); ++i) {
    const auto &a = loaded->keyframes[i], &b = path->keyframes[i];
    EXPECT_NEAR(a.t, b.t, 1e-3);
    EXPECT_NEAR(a.lat, b.lat, 1e-7);
    EXPECT_NEAR(a.lon, b.lon, 1e-7);
    EXPECT_NEAR(a.altM, b.altM, 1e-3);
    EXPECT_EQ(a.altRef, flight::AltRef::Msl);
    EXPECT_NEAR(a.headingDeg, b.headingDeg, 1e-3);
    EXPECT_NEAR(a.pitchDeg, -10.0, 1e-3);
    if (i > 0) {
      EXPECT_GT(a.t, loaded->keyframes[i - 1].t);
    }
  }
  for (const auto& e : fs::directory_iterator(dir)) EXPECT_EQ(e.path().filename(), "flown.json");
}

TEST(InteractivePathRecorder, TooShortIsAnErrorNotAFile) {
  PathRecorder rec;
  rec.start(5.0, poseAt(0.0));
  auto path = rec.stop(5.001, poseAt(0.001), "blink");
  ASSERT_FALSE(path);
  EXPECT_NE(path.error().message.find("too short"), std::string::npos);
  EXPECT_FALSE(rec.recording());
  PathRecorder idle;
  EXPECT_FALSE(idle.stop(1.0, poseAt(0.0), "never"));
}

}  // namespace
}  // namespace vegstream::app
