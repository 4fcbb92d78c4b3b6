// `vegstream fly` on a clone without ../shared (app/sample_dataset.h): with the sample lookup
// pointed at a missing directory (VEGSTREAM_SAMPLES_DIR), the headless demo generates the
// synthetic dataset once into out/datasets/synthetic, says so in one line, flies the default
// path over it with the validation layers silent, and reuses it on the next run.

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/run_command.h"
#include "tests/support/test_dirs.h"

namespace vegstream::testing {
namespace {
namespace fs = std::filesystem;

size_t occurrences(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(FlyDefaultDataset, WithoutTheSampleTheSyntheticDatasetIsMadeOnceAndReused) {
  const fs::path dir = testOutputDir();  // the working directory: out/ is made here
  const fs::path samples = dir / "no-shared-datasets";
  const std::string fly = "cd '" + dir.string() + "' && VEGSTREAM_SAMPLES_DIR='" + samples.string() + "' '" +
                          std::string(VEGSTREAM_EXE) + "' fly --headless --validate --frames 2 --size 96x54 --msaa 1";
  const fs::path dataset = dir / "out" / "datasets" / "synthetic";

  const auto first = runCommand(fly);
  ASSERT_EQ(first.exitCode, 0) << first.err;
  EXPECT_EQ(occurrences(first.err, "the Zion sample is missing"), 1u) << first.err;
  EXPECT_EQ(occurrences(first.err, "generating the synthetic dataset"), 1u) << first.err;
  EXPECT_NE(first.err.find((samples / "zion" / "srtm.tif").string()), std::string::npos) << "names what is missing";
  EXPECT_EQ(first.err.find("validation:"), std::string::npos) << first.err;
  EXPECT_EQ(first.err.find("generate "), std::string::npos) << "no progress lines of the generator";
  ASSERT_TRUE(fs::exists(dataset / "dataset.json"));
  EXPECT_FALSE(fs::exists(dir / "out" / "datasets" / "zion"));
  const auto written = fs::last_write_time(dataset / "dataset.json");
  std::ofstream(dataset / "marker") << "kept";  // regenerating would replace the directory

  const auto rec = nlohmann::json::parse(readWhole(dir / "out" / "fly" / "recording.json"));
  EXPECT_EQ(rec["dataset"]["name"], "synthetic");
  EXPECT_EQ(rec["path"]["name"], "benchmark-30s");
  EXPECT_EQ(rec["validation"]["errors"], 0);
  EXPECT_TRUE(fs::exists(dir / "out" / "fly" / "frames" / "frame_00001.png"));

  const auto second = runCommand(fly);
  ASSERT_EQ(second.exitCode, 0) << second.err;
  EXPECT_EQ(occurrences(second.err, "the Zion sample is missing"), 1u) << second.err;
  EXPECT_EQ(occurrences(second.err, "flying over the synthetic dataset in out/datasets/synthetic"), 1u)
      << second.err;
  EXPECT_EQ(second.err.find("generating"), std::string::npos) << second.err;
  EXPECT_EQ(fs::last_write_time(dataset / "dataset.json"), written);
  EXPECT_EQ(readWhole(dataset / "marker"), "kept");
}

}  // namespace
}  // namespace vegstream::testing
