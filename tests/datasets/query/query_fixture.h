#pragma once
// Shared by the query tests: the grandcanyon-xyz sample imported once per test process (ctest
// runs every test in its own process, possibly in parallel, so each gets its own directory).

#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <unistd.h>

#include "datasets/xyz_import.h"
#include "tests/support/run_command.h"

namespace vegstream::testing {

inline std::filesystem::path grandCanyonDir() { return std::filesystem::path(VEGSTREAM_DATASETS_DIR) / "grandcanyon-xyz"; }

inline std::filesystem::path testTmp(const std::string& name) {
  const auto p = std::filesystem::path(VEGSTREAM_TEST_TMP) / (name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(p);
  std::filesystem::create_directories(p.parent_path());
  return p;
}

inline datasets::XyzImportOptions grandCanyonOptions(const std::filesystem::path& out) {
  datasets::XyzImportOptions o;
  o.elevationTemplate = (grandCanyonDir() / "terrain-rgb/{z}/{x}/{y}.png").string();
  o.encoding = datasets::ElevationEncoding::TerrainRgb;
  o.imageryTemplate = (grandCanyonDir() / "map/{z}/{x}/{y}.png").string();
  o.out = out;
  o.name = "grandcanyon";
  return o;
}

// The imported dataset, made once per process.
class GrandCanyon : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new std::filesystem::path(testTmp("grandcanyon"));
    auto meta = datasets::importXyzTiles(grandCanyonOptions(*dir_), makeNullLogger());
    ASSERT_TRUE(meta.ok()) << meta.error().message;
    meta_ = new datasets::DatasetMeta(*meta);
  }
  static void TearDownTestSuite() {
    std::filesystem::remove_all(*dir_);
    delete dir_;
    delete meta_;
  }
  static const std::filesystem::path& dir() { return *dir_; }
  static const datasets::DatasetMeta& meta() { return *meta_; }

 private:
  static inline std::filesystem::path* dir_ = nullptr;
  static inline datasets::DatasetMeta* meta_ = nullptr;
};

}  // namespace vegstream::testing
