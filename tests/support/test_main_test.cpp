// tests/support/test_main.cpp, the main of every test program, through the probe programs
// (test_main_probe.cpp): a test passes only by running and passing.

#include <string>

#include <gtest/gtest.h>

#include "tests/support/run_command.h"

namespace vegstream::testing {
namespace {

CommandResult probe(const char* program, const std::string& filter) {
  return runCommand(std::string("'") + program + "' --gtest_filter=" + filter);
}

TEST(TestMain, APassingTestPasses) {
  const auto r = probe(VEGSTREAM_PROBE, "Probe.Passes");
  EXPECT_EQ(r.exitCode, 0) << r.out << r.err;
}

TEST(TestMain, ASkippedTestFails) {
  const auto r = probe(VEGSTREAM_PROBE, "Probe.Skips");
  EXPECT_EQ(r.exitCode, 1) << r.out << r.err;
  EXPECT_NE(r.err.find("1 test(s) skipped"), std::string::npos) << r.err;
}

TEST(TestMain, ATestOfASuiteThatCannotBeSetUpFails) {
  const auto r = probe(VEGSTREAM_PROBE, "ProbeSuite.WouldPass");
  EXPECT_EQ(r.exitCode, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("the probe's suite cannot be set up"), std::string::npos) << r.out;
}

TEST(TestMain, NoTestRunFails) {
  const auto r = probe(VEGSTREAM_PROBE, "NoSuch.Test");
  EXPECT_EQ(r.exitCode, 1) << r.out << r.err;
  EXPECT_NE(r.err.find("no test ran"), std::string::npos) << r.err;
}

TEST(TestMain, ADisabledTestFailsItsProgram) {
  const auto r = probe(VEGSTREAM_PROBE_WITH_DISABLED, "Probe.Passes");
  EXPECT_EQ(r.exitCode, 1) << r.out << r.err;
  EXPECT_NE(r.err.find("1 DISABLED_ test(s)"), std::string::npos) << r.err;
}

TEST(TestMain, ListingTestsIsNotARun) {
  const auto r = runCommand(std::string("'") + VEGSTREAM_PROBE_WITH_DISABLED + "' --gtest_list_tests");
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("Passes"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace vegstream::testing
