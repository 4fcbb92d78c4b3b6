// The shared simulation in the frames (issue 19), with the real executable on lavapipe over the
// Zion sample's Kolob meadow, validation on:
//  - pressed grass stays down: a ball rests in the grass for the first 0.4 s of a recording and
//    is then lifted 50 m away; at 1 s the frame still differs from a recording without it, where
//    the ball lay (the interaction field, not the live collider turn, makes the difference);
//  - the wind moves the grass: `snapshot --time 2 --wind-speed 10` differs from the calm still
//    in many pixels, and the same command twice gives the same image (deterministic in time);
//  - `--time` outside 0 … 600 is one line and exit 2.

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/read_rgb.h"
#include "tests/support/run_command.h"
#include "tests/support/test_dirs.h"
#include "tests/support/zion_sample.h"

namespace vegstream {
namespace {
namespace fs = std::filesystem;

constexpr int kW = 160, kH = 90;

std::vector<unsigned char> readRgb(const fs::path& png) { return testing::readRgb8(png, kW, kH); }

// Pixels whose colour changed by more than 24 (sum of the channels).
int changed(const std::vector<unsigned char>& a, const std::vector<unsigned char>& b) {
  if (a.size() != b.size() || a.empty()) return -1;
  int n = 0;
  for (size_t p = 0; p < a.size(); p += 3)
    n += std::abs(int(a[p]) - int(b[p])) + std::abs(int(a[p + 1]) - int(b[p + 1])) + std::abs(int(a[p + 2]) - int(b[p + 2])) > 24;
  return n;
}

// A second over the meadow, the camera 3 m up looking north and 25° down; `ball` adds a ball
// (radius 1 m) 5.5 m ahead for the first 0.4 s, then 50 m up.
fs::path writePath(const fs::path& dir, bool ball) {
  const fs::path p = dir / (ball ? "ball.json" : "calm.json");
  std::ofstream o(p);
  o << R"({"name": "press", "keyframes": [
    {"t": 0, "lat": 37.48110, "lon": -113.00950, "alt_m": 3, "heading": 0, "pitch": -25},
    {"t": 1, "lat": 37.48110, "lon": -113.00950, "alt_m": 3, "heading": 0, "pitch": -25}])";
  if (ball)
    o << R"(, "colliders": [{"name": "ball", "shape": "sphere", "radius_m": 1.0, "keyframes": [
      {"t": 0, "lat": 37.48115, "lon": -113.00950, "alt_m": 0.9},
      {"t": 0.4, "lat": 37.48115, "lon": -113.00950, "alt_m": 0.9},
      {"t": 0.45, "lat": 37.48115, "lon": -113.00950, "alt_m": 50}]}])";
  o << "}\n";
  return p;
}

TEST(SimulationFrames, PressedGrassStaysDownAfterTheColliderLeaves) {
  const auto dataset = testing::zionSampleDataset();
  ASSERT_TRUE(dataset.ok()) << dataset.error().message;
  const fs::path dir = testing::testOutputDir();
  std::vector<unsigned char> last[2];
  for (int run = 0; run < 2; ++run) {
    const fs::path out = dir / (run == 0 ? "ball" : "calm");
    const auto r = testing::runVegstream("record '" + dataset->string() + "' --path '" + writePath(dir, run == 0).string() +
                                         "' --out '" + out.string() + "' --size 160x90 --msaa 1 --fps 4 --frames-every 4 "
                                         "--validate --no-plots");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err.find("validation"), std::string::npos) << r.err;
    last[run] = readRgb(out / "frames" / "frame_00004.png");
  }
  const int n = changed(last[0], last[1]);
  std::printf("pixels changed at 1 s by the ball that left at 0.45 s: %d of %d\n", n, kW * kH);
  EXPECT_GT(n, 60);
}

std::vector<unsigned char> still(const fs::path& dataset, const std::string& name, const std::string& extra) {
  const fs::path out = testing::testOutputDir() / (name + ".png");
  const auto r = testing::runVegstream("snapshot '" + dataset.string() +
                                       "' --lat 37.4815 --lon -113.0095 --alt 1.7 --heading 90 --pitch -8 --size 160x90 "
                                       "--msaa 1 --validate --out '" + out.string() + "' " + extra);
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.err.find("validation"), std::string::npos) << r.err;
  return readRgb(out);
}

TEST(SimulationFrames, WindMovesTheGrassTheSameWayEveryTime) {
  const auto dataset = testing::zionSampleDataset();
  ASSERT_TRUE(dataset.ok()) << dataset.error().message;
  const auto calm = still(*dataset, "calm", "--time 2");
  const auto windy = still(*dataset, "windy", "--time 2 --wind-speed 10 --wind-direction 270");
  const auto again = still(*dataset, "again", "--time 2 --wind-speed 10 --wind-direction 270");
  const auto later = still(*dataset, "later", "--time 2.5 --wind-speed 10 --wind-direction 270");
  const int byWind = changed(calm, windy), byTime = changed(windy, later);
  std::printf("pixels changed: by a 10 m/s wind %d, by 0.5 s more of it %d (of %d)\n", byWind, byTime, kW * kH);
  EXPECT_GT(byWind, 500);
  EXPECT_GT(byTime, 50);  // the gusts and the blades' sway move on
  EXPECT_EQ(windy, again);
}

TEST(SimulationFrames, TimeOutsideItsRangeIsOneLineExitTwo) {
  for (const char* bad : {"-1", "601", "nan"}) {
    const fs::path out = testing::testOutputDir() / "never.png";
    const auto r = testing::runVegstream(std::string("snapshot --lat 37.48 --lon -113.01 --alt 2 --heading 0 --pitch -10 --out '") +
                                         out.string() + "' --time " + bad);
    EXPECT_EQ(r.exitCode, 2) << bad << ": " << r.err;
    EXPECT_NE(r.err.find("--time"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(out));
  }
}

}  // namespace
}  // namespace vegstream
