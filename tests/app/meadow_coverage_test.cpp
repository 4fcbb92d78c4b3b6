// Issue 18: "at eye height (1.7 m) over a grass field, blades cover at least 70 % of the ground
// within 10 m", with the default catalog and options, through the real executable on lavapipe.
//
// The view: 1.7 m above a meadow of Zion's Kolob plateau (37.4570 N, 113.0220 W, grass by the
// default catalog), looking 12° down. Two recordings of the same still, 320×180, 4× MSAA,
// validation on: `--plant-style coverage` (every plant fragment flat magenta, no shadows) and
// `--no-plants`. A pixel's coverage is how far its red and blue moved from the bare ground's
// towards 255 (the resolve blends magenta and ground by the covered samples). Ground within
// 10 m: the pixels whose ray meets the ground plane under the camera within 10 m horizontally
// (the ground is taken as the plane through its heights under the camera, 10 m ahead and 10 m
// to the right: the meadow rises about 2 m over 10 m ahead).

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <OpenImageIO/imageio.h>

#include "tests/support/run_command.h"
#include "tests/support/test_dirs.h"
#include "tests/support/zion_sample.h"

namespace vegstream {
namespace {
namespace fs = std::filesystem;
using testing::runVegstream;

constexpr double kLat = 37.4570, kLon = -113.0220, kEyeM = 1.7, kPitchDeg = -12.0, kHeadingDeg = 20.0;
constexpr double kVerticalFovDeg = 55.0;  // render/frame_types.h CameraState
constexpr int kW = 320, kH = 180, kTopRows = 15;

fs::path zionDataset() {
  const auto dir = testing::zionSampleDataset();
  if (!dir.ok()) {
    ADD_FAILURE() << dir.error().message;
    return "/nonexistent/zion";
  }
  return *dir;
}

double heightAt(const fs::path& dataset, double lat, double lon) {
  const auto r = runVegstream("query '" + dataset.string() + "' --lat " + std::to_string(lat) + " --lon " +
                              std::to_string(lon));
  EXPECT_EQ(r.exitCode, 0) << r.err;
  if (r.exitCode != 0) return NAN;
  return nlohmann::json::parse(r.out).at("height_m").get<double>();
}

// A still at the meadow (a 1 s path that moves 1 mm), frame 1 of the recording.
std::vector<unsigned char> still(const fs::path& dataset, const std::string& name, const std::string& extra) {
  const fs::path dir = testing::testOutputDir() / name;
  fs::remove_all(dir);
  const fs::path path = testing::testOutputDir() / "meadow.json";
  char keys[512];
  std::snprintf(keys, sizeof keys,
                R"({"name": "meadow", "keyframes": [
  {"t": 0, "lat": %.7f, "lon": %.7f, "alt_m": %.2f, "heading": %.1f, "pitch": %.1f},
  {"t": 1, "lat": %.7f, "lon": %.7f, "alt_m": %.2f, "heading": %.1f, "pitch": %.1f}]})",
                kLat, kLon, kEyeM, kHeadingDeg, kPitchDeg, kLat + 1e-8, kLon, kEyeM, kHeadingDeg, kPitchDeg);
  std::ofstream(path) << keys;
  // The seeding horizon is cut to 40 m: only the near plants matter here, and lavapipe is slow.
  const auto r = runVegstream("record '" + dataset.string() + "' --path '" + path.string() + "' --out '" +
                              dir.string() + "' --size " + std::to_string(kW) + "x" + std::to_string(kH) +
                              " --fps 1 --frames-every 1 --no-plots --validate --seed-horizon-m 40 " + extra);
  EXPECT_EQ(r.exitCode, 0) << r.err;
  std::ifstream meta(dir / "recording.json");
  if (meta) {
    const auto m = nlohmann::json::parse(meta);
    EXPECT_EQ(m.at("validation").at("errors").get<int>(), 0) << name;
    EXPECT_EQ(m.at("validation").at("warnings").get<int>(), 0) << name;
  } else {
    ADD_FAILURE() << "no recording.json in " << dir;
  }
  std::vector<unsigned char> rgb(size_t{kW} * kH * 3);
  auto in = OIIO::ImageInput::open((dir / "frames" / "frame_00001.png").string());
  if (!in) {
    ADD_FAILURE() << "cannot read frame 1 of " << name;
    return {};
  }
  EXPECT_EQ(in->spec().width, kW);
  EXPECT_EQ(in->spec().height, kH);
  EXPECT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, rgb.data()));
  return rgb;
}

// The ground near the camera: z = slopeAhead · (metres ahead) + slopeRight · (metres right),
// relative to the ground under the camera.
struct Ground {
  double slopeAhead = 0.0, slopeRight = 0.0;
};

// Horizontal distance (m) at which pixel (x, y)'s ray meets the ground plane, the camera kEyeM
// above it; +∞ where it does not (at and above its horizon).
double groundDistance(int x, int y, const Ground& g) {
  const double ty = std::tan(kVerticalFovDeg * M_PI / 360.0), tx = ty * kW / kH;
  const double a = ((x + 0.5) / kW * 2.0 - 1.0) * tx, b = (1.0 - (y + 0.5) / kH * 2.0) * ty;
  const double p = kPitchDeg * M_PI / 180.0;
  // Camera axes in a frame whose y is the heading and z up: right (1,0,0), up (0,−sin p, cos p),
  // forward (0, cos p, sin p).
  const double dx = a, dy = -b * std::sin(p) + std::cos(p), dz = b * std::cos(p) + std::sin(p);
  const double towards = g.slopeAhead * dy + g.slopeRight * dx - dz;  // closing speed along the ray
  if (towards <= 0.0) return INFINITY;
  return kEyeM / towards * std::hypot(dx, dy);
}

TEST(MeadowCoverage, BladesCoverSeventyPercentOfTheGroundWithinTenMetresAtEyeHeight) {
  const fs::path zion = zionDataset();
  // The ground's plane from heights 10 m ahead and 10 m right of the camera.
  const double h0 = heightAt(zion, kLat, kLon);
  auto heightOffset = [&](double headingDeg) {
    const double d = 10.0 / 111320.0, a = headingDeg * M_PI / 180.0;  // 10 m, in degrees of latitude
    return heightAt(zion, kLat + d * std::cos(a), kLon + d * std::sin(a) / std::cos(kLat * M_PI / 180.0)) - h0;
  };
  const Ground ground{heightOffset(kHeadingDeg) / 10.0, heightOffset(kHeadingDeg + 90.0) / 10.0};
  std::printf("ground slope %.2f ahead, %.2f right\n", ground.slopeAhead, ground.slopeRight);
  ASSERT_LT(std::hypot(ground.slopeAhead, ground.slopeRight), 0.35) << "a meadow, not a cliff";

  const auto covered = still(zion, "coverage", "--plant-style coverage");
  const auto bare = still(zion, "bare", "--no-plants");
  ASSERT_EQ(covered.size(), bare.size());
  ASSERT_FALSE(covered.empty());

  double sum = 0.0, top = 0.0;
  int near = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const size_t i = (size_t(y) * kW + size_t(x)) * 3;
      double f = 0.0;
      for (size_t k : {size_t{0}, size_t{2}}) {
        const double g = bare[i + k], m = covered[i + k];
        f += std::clamp((m - g) / std::max(1.0, 255.0 - g), 0.0, 1.0) / 2.0;
      }
      if (groundDistance(x, y, ground) <= 10.0) {
        sum += f;
        ++near;
      }
      if (y < kTopRows) top += f;
    }
  ASSERT_GT(near, kW * kH / 4) << "a quarter of the frame or more is ground within 10 m";
  const double coverage = sum / near;
  std::printf("meadow at eye height: %.1f %% of %d ground pixels within 10 m covered\n", 100.0 * coverage, near);
  EXPECT_GE(coverage, 0.70);
  // The measure itself: the top rows look 10–15° up, where no plant within the 40 m horizon
  // reaches: next to no magenta there (the closed forest's tree line stands in them since issue 41
  // item 6: 1.02 % of their pixels, grass seen between its trunks; it was under 1 %).
  EXPECT_LT(top / (kTopRows * kW), 0.02);
}

}  // namespace
}  // namespace vegstream

namespace vegstream {
namespace {

// Issue 18's demo: `vegstream fly` over the Zion sample flies the benchmark profile over the
// Kolob meadow (flight/paths/benchmark-30s.json, embedded), not the template's slickrock.
TEST(ZionDemo, FlyOverTheZionSampleFliesTheKolobMeadow) {
  const fs::path zion = zionDataset();
  const fs::path out = testing::testOutputDir() / "fly";
  fs::remove_all(out);
  const auto r = runVegstream("fly '" + zion.string() + "' --headless --frames 3 --size 160x90 --msaa 1 --out '" +
                              out.string() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::ifstream csv(out / "frames.csv");
  std::string header, first, second;
  ASSERT_TRUE(std::getline(csv, header) && std::getline(csv, first) && std::getline(csv, second));
  // Columns frame, t_s, lat, lon: frame 0 at t 0 s, frame 1 at t 15 s (the middle of the low phase).
  auto field = [](const std::string& line, int k) {
    std::stringstream ss(line);
    std::string f;
    for (int i = 0; i <= k; ++i) std::getline(ss, f, ',');
    return std::stod(f);
  };
  EXPECT_NEAR(field(first, 2), 37.5121, 1e-3);
  EXPECT_NEAR(field(first, 3), -112.9595, 1e-3);
  EXPECT_NEAR(field(second, 2), 37.4816, 1e-3) << "15 m over the meadow at 15 s";
  EXPECT_NEAR(field(second, 3), -112.9595, 1e-3);
}

}  // namespace
}  // namespace vegstream
