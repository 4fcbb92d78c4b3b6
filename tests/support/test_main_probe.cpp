// Not a test: a program run by test_main_test.cpp (and not registered with ctest), whose tests
// are the ways a test could pass without running. Built twice: with VEGSTREAM_PROBE_DISABLED it
// also holds a DISABLED_ test.

#include <gtest/gtest.h>

namespace {

TEST(Probe, Passes) { EXPECT_EQ(1 + 1, 2); }

TEST(Probe, Skips) { GTEST_SKIP() << "skipped by the probe"; }

class ProbeSuite : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { FAIL() << "the probe's suite cannot be set up"; }
};

TEST_F(ProbeSuite, WouldPass) { EXPECT_TRUE(true); }

#ifdef VEGSTREAM_PROBE_DISABLED
TEST(Probe, DISABLED_Off) { EXPECT_TRUE(true); }
#endif

}  // namespace
