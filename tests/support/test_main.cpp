// The main of every test program (instead of GTest::gtest_main): a test program cannot pass
// without running its tests.
//
// GoogleTest reports a GTEST_SKIP, and every test of a suite whose SetUpTestSuite failed, as
// skipped and may still exit 0; ctest shows skipped and disabled tests as "did not run" and
// still reports 100 % passed. So here the program fails (exit 1, one line saying why) when a
// test was skipped, when the program holds a DISABLED_ test, or when no test ran at all (a
// stale test list or a filter matching nothing). tests/CMakeLists.txt also keeps ctest from
// turning the "[  SKIPPED ]" line into a skip.
//
// It also points XDG_CACHE_HOME at the build's own directory (VEGSTREAM_TEST_CACHE_HOME), for
// the test program and every vegstream it starts: the impostors the suite's many runs capture
// are shared among them (render/impostor_atlas_cache.h) and never land in the developer's home.

#include <cstdio>
#include <cstdlib>

#include <gtest/gtest.h>

namespace {

// Not a test run: --gtest_list_tests (gtest_discover_tests at build time) only lists.
bool onlyListing() { return GTEST_FLAG_GET(list_tests); }

}  // namespace

int main(int argc, char** argv) {
  setenv("XDG_CACHE_HOME", VEGSTREAM_TEST_CACHE_HOME, 1);
  ::testing::InitGoogleTest(&argc, argv);
  int rc = RUN_ALL_TESTS();
  if (onlyListing()) return rc;
  const ::testing::UnitTest& u = *::testing::UnitTest::GetInstance();
  if (u.skipped_test_count() > 0) {
    std::fprintf(stderr, "[  FAILED  ] %d test(s) skipped: a skipped test fails (tests/support/test_main.cpp)\n",
                 u.skipped_test_count());
    rc = 1;
  }
  if (u.disabled_test_count() > 0) {
    std::fprintf(stderr, "[  FAILED  ] %d DISABLED_ test(s) in this program: enable or delete them\n",
                 u.disabled_test_count());
    rc = 1;
  }
  if (u.test_to_run_count() == 0) {
    std::fprintf(stderr, "[  FAILED  ] no test ran (a filter matching nothing, or a stale ctest list)\n");
    rc = 1;
  }
  return rc;
}
