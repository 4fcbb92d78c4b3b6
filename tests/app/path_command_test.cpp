// `vegstream path`: a template placed over a dataset loads as a valid flight path that lies
// inside the dataset; user mistakes end with one message, exit code 2, no file.

#include <filesystem>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "flight/flight_path_json.h"
#include "tests/app/record_test_data.h"

namespace vegstream::testing {
namespace {
namespace fs = std::filesystem;

geo::GeoBounds datasetBounds(const fs::path& ds) {
  const auto info = runVegstream("info '" + ds.string() + "'");
  EXPECT_EQ(info.exitCode, 0) << info.err;
  const auto b = nlohmann::json::parse(info.out)["bounds"];
  return {b["west"].get<double>(), b["south"].get<double>(), b["east"].get<double>(), b["north"].get<double>()};
}

TEST(PathCommand, TemplatesLoadAndLieInsideTheDataset) {
  const fs::path ds = recordDataset();
  const geo::GeoBounds bounds = datasetBounds(ds);
  for (const char* name : {"benchmark-30s", "canyon-run", "orbit"}) {
    const fs::path out = freshRecordDir(std::string("path_") + name + ".json");
    const auto r =
        runVegstream("path --dataset '" + ds.string() + "' --template " + name + " --out '" + out.string() + "'");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    auto path = flight::loadFlightPath(out);
    ASSERT_TRUE(path) << path.error().message;
    EXPECT_EQ(path->name, name);
    EXPECT_TRUE(flight::checkInside(*path, bounds)) << name;
    if (std::string(name) == "benchmark-30s") {
      EXPECT_DOUBLE_EQ(path->duration(), 30.0);
    }
  }
}

TEST(PathCommand, UserMistakesExitTwoWithOneLineAndNoFile) {
  const fs::path out = freshRecordDir("path_bad.json");
  for (const std::string& args :
       std::vector<std::string>{"--dataset /no/such/dataset --template benchmark-30s",
                                "--dataset '" + recordDataset().string() + "' --template nope"}) {
    const auto r = runVegstream("path " + args + " --out '" + out.string() + "'");
    EXPECT_EQ(r.exitCode, 2) << args << ": " << r.err;
    EXPECT_EQ(countLines(r.err), 1) << r.err;
    EXPECT_FALSE(fs::exists(out)) << args;
  }
}

}  // namespace
}  // namespace vegstream::testing
