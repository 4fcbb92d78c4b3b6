// `vegstream fly` as a user runs it: the headless demo writes a recording (frames.csv,
// recording.json, summary.json, every frame as PNG) like `record`'s, with the validation layers
// silent, and replaces only an earlier recording; user mistakes end with one message, exit
// code 2, nothing written.

#include <algorithm>
#include <filesystem>
#include <map>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "flight/record_table.h"
#include "tests/support/run_command.h"
#include "tests/support/test_dirs.h"
#include "tests/support/zion_sample.h"
#include "tests/support/virtual_display.h"

namespace vegstream::testing {
namespace {
namespace fs = std::filesystem;

Result<fs::path> zionDataset() { return zionSampleDataset(); }

// Every fly test runs over the imported Zion sample: a test whose dataset could not be made fails.
class FlyCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto zion = zionDataset();
    ASSERT_TRUE(zion.ok()) << zion.error().message;
    zion_ = zion->string();
  }
  std::string zion_;
};

// Column `name` of the recording's frames.csv, every row (empty cells as NaN).
std::vector<double> column(const fs::path& recording, const std::string& name) {
  auto table = flight::RecordTable::loadCsv(recording / "frames.csv");
  EXPECT_TRUE(table.ok()) << table.error().message;
  std::vector<double> out;
  if (!table.ok()) return out;
  const auto c = table->find(name);
  EXPECT_TRUE(c.has_value()) << name;
  if (!c) return out;
  for (std::size_t i = 0; i < table->rowCount(); ++i) out.push_back(table->at(i, *c));
  return out;
}

TEST_F(FlyCommand, HeadlessDemoWritesARecordingWithValidationSilent) {
  const fs::path out = testOutputDir() / "out";
  const auto r = runVegstream("fly '" + zion_ + "' --headless --validate --frames 3 --size 160x90 --msaa 1 " +
                              "--blade-path auto --out '" + out.string() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  for (const char* f : {"frames/frame_00000.png", "frames/frame_00001.png", "frames/frame_00002.png", "frames.csv",
                        "recording.json", "summary.json"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  EXPECT_FALSE(fs::exists(out / "run.json"));
  const auto rec = nlohmann::json::parse(readWhole(out / "recording.json"));
  EXPECT_EQ(rec["validation"]["errors"], 0);
  EXPECT_EQ(rec["validation"]["warnings"], 0);
  EXPECT_EQ(rec["size"][0], 160);
  EXPECT_EQ(rec["path"]["name"], "benchmark-30s");
  EXPECT_EQ(rec["streaming"]["mode"], "settled");
  EXPECT_EQ(rec["plants"]["blade_path"], "compute");
  EXPECT_FALSE(rec["device"]["name"].get<std::string>().empty());
  const auto summary = nlohmann::json::parse(readWhole(out / "summary.json"));
  EXPECT_EQ(summary["frames"], 3);
  // The three frames span the path: its start, middle and end.
  EXPECT_EQ(column(out, "t_s"), (std::vector<double>{0.0, 15.0, 30.0}));
  // Zion streamed: headless frames are settled, so every piece is drawn from its own tiles.
  for (double v : column(out, "terrain_triangles")) EXPECT_GT(v, 500.0);  // ROAM at 2 px on 160 × 90 (the Kolob meadow is smooth)
  for (double v : column(out, "terrain_pieces")) EXPECT_GT(v, 2.0);
  for (double v : column(out, "terrain_fallback_pieces")) EXPECT_EQ(v, 0.0);
  for (double v : column(out, "gpu_bytes")) EXPECT_GT(v, 0.0);
  EXPECT_EQ(r.err.find("validation:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("device:"), std::string::npos) << "the chosen device is printed";
  // Nothing temporary is left behind.
  for (const auto& e : fs::directory_iterator(out.parent_path()))
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
}

TEST_F(FlyCommand, AnEarlierRecordingIsReplacedAnythingElseIsRefused) {
  const fs::path dir = testOutputDir();
  const fs::path out = dir / "out";
  const std::string args =
      "fly '" + zion_ + "' --headless --frames 2 --size 96x54 --msaa 1 --out '" + out.string() + "'";
  ASSERT_EQ(runVegstream(args).exitCode, 0);
  const auto again = runVegstream(args);  // the demo run twice: the second replaces the first
  ASSERT_EQ(again.exitCode, 0) << again.err;
  EXPECT_TRUE(fs::exists(out / "frames.csv"));
  EXPECT_EQ(column(out, "t_s").size(), 2u);
  EXPECT_FALSE(fs::exists(dir / "out.replaced"));

  const fs::path other = dir / "other";
  fs::create_directories(other);
  std::ofstream(other / "notes.txt") << "mine";
  const auto refused =
      runVegstream("fly '" + zion_ + "' --headless --frames 2 --size 96x54 --msaa 1 --out '" + other.string() + "'");
  EXPECT_EQ(refused.exitCode, 2) << refused.err;
  EXPECT_EQ(countLines(refused.err), 1) << refused.err;
  EXPECT_NE(refused.err.find("--out"), std::string::npos) << refused.err;
  EXPECT_EQ(readWhole(other / "notes.txt"), "mine");
}

struct BadInput {
  const char* name;
  std::string args;
  const char* mentions;
};

// {ZION} in `args` stands for the imported dataset (the parameters are made at static
// initialisation, before any dataset exists).
class FlyBadInput : public ::testing::TestWithParam<BadInput> {};

TEST_P(FlyBadInput, OneMessageExitTwoNothingWritten) {
  const fs::path out = testOutputDir() / "out";
  std::string args = GetParam().args;
  if (const size_t at = args.find("{ZION}"); at != std::string::npos) {
    const auto zion = zionDataset();
    ASSERT_TRUE(zion.ok()) << zion.error().message;
    args.replace(at, 6, zion->string());
  }
  const auto r = runVegstream("fly " + args + " --headless --frames 2 --out '" + out.string() + "'");
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_EQ(countLines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(GetParam().mentions), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out)) << "nothing may be written on a user mistake";
}

INSTANTIATE_TEST_SUITE_P(
    Cases, FlyBadInput,
    ::testing::Values(BadInput{"missing_dataset", "/no/such/dataset", "/no/such/dataset"},
                      BadInput{"not_a_dataset", "'" + std::string(VEGSTREAM_DATASETS_DIR) + "/zion'", "dataset.json"},
                      BadInput{"missing_path", "'{ZION}' --path /no/such/path.json", "/no/such/path.json"},
                      BadInput{"unknown_device", "'{ZION}' --device no-such-gpu", "no-such-gpu"},
                      BadInput{"size_zero", "'{ZION}' --size 0x90", "--size"},
                      BadInput{"size_garbage", "'{ZION}' --size big", "--size"},
                      BadInput{"size_too_large", "'{ZION}' --size 99999x90", "--size"},
                      BadInput{"msaa_three", "'{ZION}' --msaa 3", "--msaa"},
                      // lavapipe offers 1 and 4 samples only
                      BadInput{"msaa_unoffered", "'{ZION}' --device llvmpipe --msaa 8", "--msaa 8"},
                      // no mesh-shader blade path in this build: the line names the option, the device and why
                      BadInput{"blade_path_mesh", "'{ZION}' --device llvmpipe --blade-path mesh",
                               "--blade-path mesh is not available on llvmpipe"}),
    [](const auto& testInfo) { return std::string(testInfo.param.name); });

TEST_F(FlyCommand, BothBladePathsRecordTheSamePlantsAndTriangles) {
  // --blade-path tessellation and compute over the same frames: the same plants and plant
  // triangles per frame; only the compute path has the expansion pass (gpu_blades_ms).
  const fs::path dir = testOutputDir();
  std::map<std::string, nlohmann::json> rec;
  for (const char* path : {"tessellation", "compute"}) {
    const fs::path out = dir / path;
    const auto r = runVegstream("fly '" + zion_ + "' --headless --validate --frames 3 --size 160x90 --msaa 1 " +
                                "--blade-path " + path + " --out '" + out.string() + "'");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err.find("validation:"), std::string::npos) << r.err;
    rec[path] = nlohmann::json::parse(readWhole(out / "recording.json"));
    EXPECT_EQ(rec[path]["plants"]["blade_path"], path);
    EXPECT_EQ(rec[path]["plants"]["blade_path_requested"], path);
  }
  const auto blades = [&](const char* p) {
    const auto passes = rec[p]["gpu_passes"].get<std::vector<std::string>>();
    return std::count(passes.begin(), passes.end(), "blades");
  };
  EXPECT_EQ(blades("compute"), 1);
  EXPECT_EQ(blades("tessellation"), 0);
  const auto plantsT = column(dir / "tessellation", "plants"), plantsC = column(dir / "compute", "plants");
  const auto trisT = column(dir / "tessellation", "plant_triangles");
  const auto trisC = column(dir / "compute", "plant_triangles");
  ASSERT_EQ(plantsT.size(), 3u);
  double drawn = 0.0;
  for (size_t i = 0; i < plantsT.size(); ++i) {
    EXPECT_EQ(plantsT[i], plantsC[i]) << "frame " << i;
    EXPECT_EQ(trisT[i], trisC[i]) << "frame " << i;
    drawn += trisC[i];
  }
  EXPECT_GT(drawn, 0.0) << "some frame drew plants";
}

TEST_F(FlyCommand, WindowModeUnderAVirtualDisplay) {
  const fs::path dir = testOutputDir();
  auto display = VirtualDisplay::start(dir / "xvfb.log");
  ASSERT_TRUE(display.ok()) << display.error().message;
  const auto r = runCommand((*display)->environment() + "'" + std::string(VEGSTREAM_EXE) + "' fly '" + zion_ +
                            "' --validate --frames 4 --size 160x90 --msaa 1");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("window open"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("window closed after 4 frames"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("validation:"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace vegstream::testing

namespace vegstream::testing {
namespace {

TEST_F(FlyCommand, APathOutsideTheDatasetIsRefusedWithOneLine) {
  const fs::path dir = testOutputDir();
  const fs::path path = dir / "elsewhere.json";
  std::ofstream(path) << R"({"name": "elsewhere", "keyframes": [
    {"t": 0, "lat": 46.5, "lon": 7.9, "alt_m": 300, "heading": 0, "pitch": -10},
    {"t": 10, "lat": 46.6, "lon": 7.9, "alt_m": 300, "heading": 0, "pitch": -10}]})";
  const fs::path out = dir / "out";
  const auto r =
      runVegstream("fly '" + zion_ + "' --headless --path '" + path.string() + "' --out '" + out.string() + "'");
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_EQ(countLines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("keyframes[0]"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(FlyCommand, PlaysAGivenPathHeadless) {
  const fs::path dir = testOutputDir();
  const fs::path path = dir / "short.json";
  std::ofstream(path) << R"({"name": "short", "keyframes": [
    {"t": 0, "lat": 37.25, "lon": -113.05, "alt_m": 400, "heading": 90, "pitch": -15},
    {"t": 4, "lat": 37.25, "lon": -113.00, "alt_m": 400, "heading": 90, "pitch": -15}]})";
  const fs::path out = dir / "out";
  const auto r = runVegstream("fly '" + zion_ + "' --headless --validate --frames 2 --size 96x54 --msaa 1 --path '" +
                              path.string() + "' --out '" + out.string() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto rec = nlohmann::json::parse(readWhole(out / "recording.json"));
  EXPECT_EQ(rec["path"]["name"], "short");
  EXPECT_EQ(rec["validation"]["errors"], 0);
  EXPECT_TRUE(fs::exists(out / "frames/frame_00001.png"));
}

}  // namespace
}  // namespace vegstream::testing
