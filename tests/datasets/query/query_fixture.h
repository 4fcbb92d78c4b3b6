#pragma once
// Shared by the query tests: the grandcanyon-xyz sample imported once per build of this test
// program for all its test processes (cachedFixture), and each test's own scratch directory.

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "datasets/dataset_format.h"
#include "datasets/xyz_import.h"
#include "tests/support/run_command.h"
#include "tests/support/test_dirs.h"

namespace vegstream::testing {

inline std::filesystem::path grandCanyonDir() {
  return std::filesystem::path(VEGSTREAM_DATASETS_DIR) / "grandcanyon-xyz";
}

// `name` in the running test's own directory, not there yet.
inline std::filesystem::path testTmp(const std::string& name) {
  const auto p = testOutputDir() / name;
  std::filesystem::remove_all(p);
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

// The imported dataset; a test that cannot have it fails (made in SetUp: GoogleTest turns a
// failed SetUpTestSuite into skipped tests).
class GrandCanyon : public ::testing::Test {
 protected:
  void SetUp() override {
    auto dir = cachedFixture("query-grandcanyon", programKey(), [](const std::filesystem::path& out) -> Status {
      auto meta = datasets::importXyzTiles(grandCanyonOptions(out), makeNullLogger());
      if (!meta.ok()) return meta.error();
      return {};
    });
    ASSERT_TRUE(dir.ok()) << dir.error().message;
    dir_ = *dir;
    auto meta = datasets::readDatasetMeta(dir_);
    ASSERT_TRUE(meta.ok()) << meta.error().message;
    meta_ = *meta;
  }
  const std::filesystem::path& dir() const { return dir_; }
  const datasets::DatasetMeta& meta() const { return meta_; }

 private:
  std::filesystem::path dir_;
  datasets::DatasetMeta meta_;
};

}  // namespace vegstream::testing
