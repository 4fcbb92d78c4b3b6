// `vegstream inspect` (app/inspect_command.h) through the real executable: the blade shape of core
// seed ../shared/seeds/001_3eca9f2c7752e4fb.txt §2.3 as JSON (N hinge angles, N + 1 unit-spaced
// points, the residual, the buckling stiffness), and every user mistake is one message naming
// the option (or listing the topics), exit 2, nothing on stdout.

#include <cmath>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/run_command.h"

namespace vegstream::testing {
namespace {
using nlohmann::json;

TEST(InspectCommand, BladeShapeIsJsonOfTheSolvedShape) {
  const auto r = runVegstream("inspect blade-shape --stiffness 5 --segments 4");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["stiffness"].get<double>(), 5.0);
  EXPECT_EQ(j["segments"].get<int>(), 4);
  EXPECT_EQ(j["root_tilt"].get<double>(), 0.1);
  ASSERT_EQ(j["phi"].size(), 4u);
  ASSERT_EQ(j["inclination"].size(), 4u);
  ASSERT_EQ(j["points"].size(), 5u);
  EXPECT_LT(j["residual"].get<double>(), 1e-9);
  EXPECT_NEAR(j["critical_stiffness"].get<double>(), 11.9208395, 1e-6);
  EXPECT_EQ(j["points"][0][0].get<double>(), 0.0);
  EXPECT_EQ(j["points"][0][1].get<double>(), 0.0);
  double theta = 0.0;
  for (size_t i = 0; i < 4; ++i) {
    theta += j["phi"][i].get<double>();
    const double dx = j["points"][i + 1][0].get<double>() - j["points"][i][0].get<double>();
    const double dy = j["points"][i + 1][1].get<double>() - j["points"][i][1].get<double>();
    EXPECT_NEAR(std::hypot(dx, dy), 1.0, 1e-12);
    EXPECT_NEAR(dx, std::sin(theta), 1e-12);
    EXPECT_NEAR(j["inclination"][i].get<double>(), theta, 1e-12);
  }
  const auto tilted = runVegstream("inspect blade-shape --stiffness 1e6 --segments 2 --root-tilt 0.3");
  ASSERT_EQ(tilted.exitCode, 0) << tilted.err;
  EXPECT_NEAR(json::parse(tilted.out)["phi"][0].get<double>(), 0.3, 1e-5);
}

void expectUserError(const std::string& args, const std::string& named) {
  const auto r = runVegstream(args);
  EXPECT_EQ(r.exitCode, 2) << args;
  EXPECT_EQ(countLines(r.err), 1) << args << ": " << r.err;
  EXPECT_NE(r.err.find(named), std::string::npos) << args << ": " << r.err;
  EXPECT_TRUE(r.out.empty()) << args;
}

TEST(InspectCommand, BadValuesAreOneMessageNamingTheOption) {
  expectUserError("inspect blade-shape --segments 4", "--stiffness");
  for (const char* k : {"0", "-1", "abc", "nan", "inf", "5x"})
    expectUserError(std::string("inspect blade-shape --stiffness ") + k, "--stiffness");
  for (const char* n : {"0", "17", "2.5", "four", "-3"})
    expectUserError(std::string("inspect blade-shape --stiffness 1 --segments ") + n, "--segments");
  for (const char* t : {"-0.1", "1.6", "x"})
    expectUserError(std::string("inspect blade-shape --stiffness 1 --root-tilt ") + t, "--root-tilt");
}

TEST(InspectCommand, NoOrUnknownTopicListsTheTopics) {
  expectUserError("inspect", "blade-shape");
  expectUserError("inspect leaf-colour", "leaf-colour");
  expectUserError("inspect leaf-colour", "blade-shape");
}

}  // namespace
}  // namespace vegstream::testing
