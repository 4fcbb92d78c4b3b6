// `vegstream fly` as a user runs it: the headless demo writes frames and run.json with the
// validation layers silent; user mistakes end with one message, exit code 2, nothing written.

#include <filesystem>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/run_command.h"

namespace vegstream::testing {
namespace {
namespace fs = std::filesystem;

fs::path freshDir(const std::string& name) {
  const fs::path dir = fs::path(VEGSTREAM_TEST_TMP) / name;
  fs::remove_all(dir);
  return dir;
}

const std::string kZion = std::string(VEGSTREAM_DATASETS_DIR) + "/zion";

TEST(FlyCommand, HeadlessDemoWritesFramesAndRunJsonWithValidationSilent) {
  const fs::path out = freshDir("fly_ok");
  const auto r = runVegstream("fly '" + kZion + "' --headless --validate --frames 3 --size 160x90 --msaa 1 --out '" +
                              out.string() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  for (const char* f : {"frame_0000.png", "frame_0001.png", "frame_0002.png", "run.json"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  const auto run = nlohmann::json::parse(readWhole(out / "run.json"));
  EXPECT_EQ(run["frames"], 3);
  EXPECT_EQ(run["validation"]["errors"], 0);
  EXPECT_EQ(run["validation"]["warnings"], 0);
  EXPECT_EQ(run["size"][0], 160);
  // The Zion DEM is 465 × 457 samples with no nodata: 2 · 464 · 456 triangles.
  EXPECT_EQ(run["terrain_triangles"], 2 * 464 * 456);
  EXPECT_FALSE(run["device"]["name"].get<std::string>().empty());
  EXPECT_EQ(r.err.find("validation:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("device:"), std::string::npos) << "the chosen device is printed";
  // Nothing temporary is left behind.
  for (const auto& e : fs::directory_iterator(out)) EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos);
}

struct BadInput {
  const char* name;
  std::string args;
  const char* mentions;
};

class FlyBadInput : public ::testing::TestWithParam<BadInput> {};

TEST_P(FlyBadInput, OneMessageExitTwoNothingWritten) {
  const fs::path out = freshDir(std::string("fly_bad_") + GetParam().name);
  const auto r = runVegstream("fly " + GetParam().args + " --headless --frames 2 --out '" + out.string() + "'");
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_EQ(countLines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(GetParam().mentions), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out)) << "nothing may be written on a user mistake";
}

INSTANTIATE_TEST_SUITE_P(
    Cases, FlyBadInput,
    ::testing::Values(
        BadInput{"missing_dataset", "/no/such/dataset", "/no/such/dataset"},
        BadInput{"not_a_dem", "'" + std::string(VEGSTREAM_DATASETS_DIR) + "/README.md'", "README.md"},
        BadInput{"unknown_device", "'" + kZion + "' --device no-such-gpu", "no-such-gpu"},
        BadInput{"size_zero", "'" + kZion + "' --size 0x90", "--size"},
        BadInput{"size_garbage", "'" + kZion + "' --size big", "--size"},
        BadInput{"size_too_large", "'" + kZion + "' --size 99999x90", "--size"},
        BadInput{"msaa_three", "'" + kZion + "' --msaa 3", "--msaa"},
        // lavapipe offers 1 and 4 samples only
        BadInput{"msaa_unoffered", "'" + kZion + "' --device llvmpipe --msaa 8", "--msaa 8"}),
    [](const auto& testInfo) { return std::string(testInfo.param.name); });

TEST(FlyCommand, WindowModeUnderAVirtualDisplay) {
  if (std::system("command -v xvfb-run >/dev/null 2>&1") != 0) FAIL() << "xvfb-run missing: run scripts/setup";
  const auto r = runCommand("xvfb-run -a '" + std::string(VEGSTREAM_EXE) + "' fly '" + kZion +
                            "' --validate --frames 4 --size 160x90 --msaa 1");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("window open"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("window closed after 4 frames"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("validation:"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace vegstream::testing
