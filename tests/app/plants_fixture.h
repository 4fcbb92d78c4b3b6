#pragma once
// Shared by the `vegstream plants` tests (plants_command_test.cpp, plants_export_test.cpp): a
// 2 km synthetic dataset made once per build for every test process, boxes about its centre,
// and each test's own scratch directory.

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/run_command.h"
#include "tests/support/test_dirs.h"

namespace vegstream::testing {

// `name` in the running test's own directory, not there yet.
inline std::filesystem::path testTmp(const std::string& name) {
  const auto p = testOutputDir() / name;
  std::filesystem::remove_all(p);
  return p;
}
inline std::string q(const std::filesystem::path& p) { return "'" + p.string() + "'"; }

class Plants : public ::testing::Test {
 protected:
  // A 2 km synthetic dataset (max zoom 13), made once per build for all test
  // processes; the box: 100 m × 100 m at its centre. Made in SetUp (not SetUpTestSuite, whose
  // failure GoogleTest turns into skipped tests): a test without its dataset fails.
  void SetUp() override {
    auto dir = cachedFixture("plants-synthetic-2km", vegstreamKey(), [](const std::filesystem::path& out) -> Status {
      const auto g = runVegstream("generate --out " + q(out) + " --name synth --size-km 2 --max-zoom 13 --seed 7");
      if (g.exitCode != 0) return makeError(ErrorKind::Internal, "vegstream generate: " + g.err);
      return {};
    });
    ASSERT_TRUE(dir.ok()) << dir.error().message;
    dir_ = *dir;
    const auto info = runVegstream("info " + q(dir_));
    ASSERT_EQ(info.exitCode, 0) << info.err;
    const nlohmann::json j = nlohmann::json::parse(info.out);
    lat_ = 0.5 * (j["bounds"]["south"].get<double>() + j["bounds"]["north"].get<double>());
    lon_ = 0.5 * (j["bounds"]["west"].get<double>() + j["bounds"]["east"].get<double>());
  }
  std::string bbox(double halfM, double offsetEastM = 0.0) const {
    const double dLat = halfM / 111000.0, mLon = 111000.0 * std::cos(lat_ * M_PI / 180.0);
    const double dLon = halfM / mLon, c = lon_ + offsetEastM / mLon;
    char buf[160];
    std::snprintf(buf, sizeof(buf), "%.9f,%.9f,%.9f,%.9f", c - dLon, lat_ - dLat, c + dLon, lat_ + dLat);
    return buf;
  }
  static std::vector<double> numbers(const std::string& box) {
    std::vector<double> v;
    std::stringstream ss(box);
    for (std::string c; std::getline(ss, c, ',');) v.push_back(std::stod(c));
    return v;
  }
  std::string plants(const std::string& args) const { return "plants " + q(dir_) + " " + args; }

  std::filesystem::path dir_;
  double lat_ = 0.0, lon_ = 0.0;
};

}  // namespace vegstream::testing
