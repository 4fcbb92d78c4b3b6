// `vegstream fly` in a window under a virtual display (xvfb-run): N frames with the validation
// layers silent, the HUD drawn into the presented image (a screenshot of the same frame with
// and without the HUD differs in the HUD's corner and not far from it), and the screenshot a
// PNG named by time and counter; the shared simulation's window inputs (issue 19): the camera's
// collider, and a path's own colliders and wind sources, in a windy flight.

#include <cstdlib>
#include <filesystem>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "app/path_recorder.h"
#include "flight/flight_path_json.h"
#include "tests/support/run_command.h"
#include "tests/support/test_dirs.h"
#include "tests/support/virtual_display.h"

namespace vegstream::testing {
namespace {
namespace fs = std::filesystem;

class InteractiveWindow : public ::testing::Test {
 protected:
  // A 3 km synthetic dataset made by this build's vegstream, once for all test processes; a
  // test whose dataset or virtual display could not be made fails.
  void SetUp() override {
    auto dataset = cachedFixture("interactive-synthetic-3km", vegstreamKey(), [](const fs::path& dir) -> Status {
      const auto r = runVegstream("generate --out '" + dir.string() + "' --size-km 3 --seed 2");
      if (r.exitCode != 0) return makeError(ErrorKind::Internal, "vegstream generate: " + r.err);
      return {};
    });
    ASSERT_TRUE(dataset.ok()) << dataset.error().message;
    dataset_ = *dataset;
    dir_ = testOutputDir();
    auto display = VirtualDisplay::start(dir_ / "xvfb.log");
    ASSERT_TRUE(display.ok()) << display.error().message;
    display_ = std::move(*display);
  }

  // Runs 3 window frames at 320×180 with a screenshot of frame 3; returns the PNG's pixels. The
  // exposure is fixed: the window's automatic one adapts over session time, which differs run to
  // run, and the comparison is of the HUD alone.
  std::vector<uint8_t> screenshot(const std::string& name, bool hud, std::string* err) {
    const fs::path out = dir_ / name;
    fs::create_directories(out);
    const std::string env = std::string("VEGSTREAM_FLY_SCREENSHOT_FRAME=3 ") + (hud ? "" : "VEGSTREAM_FLY_NO_HUD=1 ");
    const auto r = runCommand("cd '" + out.string() + "' && " + display_->environment() + env + "'" + VEGSTREAM_EXE +
                              "' fly '" + dataset_.string() + "' --validate --frames 3 --size 320x180 --msaa 1 --exposure 14");
    *err = r.err;
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("window closed after 3 frames"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("validation:"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("screenshot saved: "), std::string::npos) << r.err;
    std::vector<fs::path> pngs;
    for (const auto& e : fs::directory_iterator(out))
      if (e.path().extension() == ".png") pngs.push_back(e.path());
    EXPECT_EQ(pngs.size(), 1u);
    if (pngs.empty()) return {};
    EXPECT_EQ(pngs[0].filename().string().rfind("vegstream-", 0), 0u) << pngs[0];
    auto in = OIIO::ImageInput::open(pngs[0].string());
    EXPECT_TRUE(in);
    if (!in) return {};
    const OIIO::ImageSpec& spec = in->spec();
    EXPECT_EQ(spec.width, 320);
    EXPECT_EQ(spec.height, 180);
    std::vector<uint8_t> px(size_t(spec.width) * spec.height * 4);
    in->read_image(0, 0, 0, 4, OIIO::TypeDesc::UINT8, px.data());
    return px;
  }

  fs::path dataset_, dir_;
  std::unique_ptr<VirtualDisplay> display_;
};

TEST_F(InteractiveWindow, HudIsDrawnAndValidationSilent) {
  std::string errHud, errPlain;
  const auto withHud = screenshot("interactive_hud", true, &errHud);
  const auto without = screenshot("interactive_nohud", false, &errPlain);
  ASSERT_EQ(withHud.size(), 320u * 180u * 4u);
  ASSERT_EQ(without.size(), withHud.size());
  // The HUD panel starts 6 px from the top-left corner (at 320×180 it reaches the other
  // edges): most of its pixels change; the margin left of it stays the same frame.
  auto changedShare = [&](int x0, int y0, int x1, int y1) {
    int changed = 0, total = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        const size_t i = (size_t(y) * 320 + size_t(x)) * 4;
        int d = 0;
        for (int c = 0; c < 3; ++c) d += std::abs(int(withHud[i + size_t(c)]) - int(without[i + size_t(c)]));
        changed += d > 12;
        ++total;
      }
    return double(changed) / total;
  };
  EXPECT_GT(changedShare(8, 8, 120, 60), 0.5) << "the HUD darkens and writes over its panel";
  EXPECT_LT(changedShare(0, 0, 4, 180), 0.05) << "beside the panel the frame is the same";
}

// The window with the camera's collider walking (VEGSTREAM_FLY_COLLIDER, as C would set it) over
// a path whose collider and whirlwind move on session time, in a 12 m/s gusty wind: the frames
// run through the simulation with the validation layers silent.
TEST_F(InteractiveWindow, CameraColliderAndPathCollidersInAWindyFlight) {
  const fs::path pathFile = dir_ / "windy.json";
  const auto made = runVegstream("path --dataset '" + dataset_.string() + "' --out '" + pathFile.string() + "'");
  ASSERT_EQ(made.exitCode, 0) << made.err;
  auto path = flight::loadFlightPath(pathFile);
  ASSERT_TRUE(path.ok()) << path.error().message;
  const flight::Keyframe& k = path->keyframes.front();
  const flight::Keyframe& next = path->keyframes[1];  // inside the dataset, as the path is
  flight::Collider ball;
  ball.name = "ball";
  ball.radiusM = 1.5;
  ball.keyframes = {{0.0, k.lat, k.lon, 1.5, flight::AltRef::Terrain},
                    {10.0, next.lat, next.lon, 1.5, flight::AltRef::Terrain}};
  path->colliders.push_back(ball);
  flight::WindSourceSpec whirl;
  whirl.name = "whirl";
  whirl.type = flight::WindSourceSpec::Type::Whirlwind;
  whirl.radiusM = 20.0;
  whirl.strengthMps = 15.0;
  whirl.keyframes = {{0.0, k.lat, k.lon, 5.0, flight::AltRef::Terrain}};
  path->wind = flight::WindSection{};
  path->wind->sources.push_back(whirl);
  ASSERT_TRUE(app::saveFlightPath(*path, pathFile).ok());

  const auto r =
      runCommand("cd '" + dir_.string() + "' && " + display_->environment() + "VEGSTREAM_FLY_COLLIDER=walking '" +
                 VEGSTREAM_EXE + "' fly '" + dataset_.string() + "' --path '" + pathFile.string() +
                 "' --wind-speed 12 --gustiness 0.8 --validate --frames 3 --size 320x180 --msaa 1");
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("window closed after 3 frames"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("camera collider: walking (radius 0.35 m, length 1.1 m, 1.5 m ahead)"), std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("validation:"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace vegstream::testing
