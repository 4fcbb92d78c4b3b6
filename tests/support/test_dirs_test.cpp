// The tests' own plumbing (tests/support/test_dirs.h): each test's directory, and fixtures
// made once, by one maker at a time, keyed to the build that made them.

#include "tests/support/test_dirs.h"

#include <atomic>
#include <fstream>
#include <future>
#include <thread>

#include <gtest/gtest.h>

namespace vegstream::testing {
namespace {
namespace fs = std::filesystem;

// Makes `dir` holding one file; counts the calls.
std::function<Status(const fs::path&)> counting(std::atomic<int>& calls) {
  return [&calls](const fs::path& dir) -> Status {
    ++calls;
    fs::create_directories(dir);
    std::ofstream(dir / "made.txt") << "made";
    return {};
  };
}

// A fixture name no other test (or earlier run) uses.
std::string uniqueName(const std::string& what) {
  return what + "-" + std::to_string(::getpid()) + "-" +
         ::testing::UnitTest::GetInstance()->current_test_info()->name();
}

TEST(TestOutputDir, IsTheTestsOwnAndEmptiedOnlyByTheFirstCall) {
  const fs::path dir = testOutputDir();
  EXPECT_NE(dir.filename().string().find("TestOutputDir.IsTheTestsOwnAndEmptiedOnlyByTheFirstCall"), std::string::npos)
      << dir;
  EXPECT_TRUE(fs::is_empty(dir));
  std::ofstream(dir / "kept.txt") << "x";
  EXPECT_EQ(testOutputDir(), dir);
  EXPECT_TRUE(fs::exists(dir / "kept.txt")) << "a second call in the same test keeps what the test wrote";
}

TEST(CachedFixture, IsMadeOnceAndReused) {
  std::atomic<int> calls = 0;
  const std::string name = uniqueName("once");
  auto a = cachedFixture(name, "maker-1", counting(calls));
  ASSERT_TRUE(a.ok()) << a.error().message;
  auto b = cachedFixture(name, "maker-1", counting(calls));
  ASSERT_TRUE(b.ok()) << b.error().message;
  EXPECT_EQ(*a, *b);
  EXPECT_EQ(calls, 1);
  EXPECT_TRUE(fs::exists(*a / "made.txt"));
  fs::remove_all(*a);
}

TEST(CachedFixture, ConcurrentUsersGetOneMakerAndTheSameDirectory) {
  std::atomic<int> calls = 0;
  const std::string name = uniqueName("concurrent");
  std::promise<void> otherStarted;
  std::shared_future<void> started = otherStarted.get_future().share();
  // The first maker waits until the other user has started asking (it then blocks on the lock
  // or finds the fixture made): one make either way.
  auto slowMaker = [&](const fs::path& dir) -> Status {
    started.wait();
    return counting(calls)(dir);
  };
  auto first = std::async(std::launch::async, [&] { return cachedFixture(name, "maker-1", slowMaker); });
  auto second = std::async(std::launch::async, [&] {
    otherStarted.set_value();
    return cachedFixture(name, "maker-1", counting(calls));
  });
  const auto a = first.get(), b = second.get();
  ASSERT_TRUE(a.ok()) << a.error().message;
  ASSERT_TRUE(b.ok()) << b.error().message;
  EXPECT_EQ(*a, *b);
  EXPECT_EQ(calls, 1);
  fs::remove_all(*a);
}

TEST(CachedFixture, AFailedMakeLeavesNothingAndIsTriedAgain) {
  const std::string name = uniqueName("failing");
  auto bad = cachedFixture(name, "maker-1", [](const fs::path& dir) -> Status {
    fs::create_directories(dir);
    std::ofstream(dir / "half.txt") << "half";
    return makeError(ErrorKind::Io, "disk full");
  });
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find(name), std::string::npos) << bad.error().message;
  EXPECT_NE(bad.error().message.find("disk full"), std::string::npos) << bad.error().message;
  for (const auto& e : fs::directory_iterator(fs::path(VEGSTREAM_TEST_TMP) / "fixtures")) {
    const std::string n = e.path().filename().string();
    if (n.rfind(name + ".", 0) == 0) {
      EXPECT_TRUE(n.ends_with(".lock")) << "left behind: " << n;
    }
  }
  std::atomic<int> calls = 0;
  auto good = cachedFixture(name, "maker-1", counting(calls));
  ASSERT_TRUE(good.ok()) << good.error().message;
  EXPECT_EQ(calls, 1);
  fs::remove_all(*good);
}

TEST(CachedFixture, ANewBuildMakesItAgainAndDropsTheOlderBuildsOfTheSameMaker) {
  std::atomic<int> calls = 0;
  const std::string name = uniqueName("rebuilt");
  auto old = cachedFixture(name, "maker-aaaa", counting(calls));
  auto other = cachedFixture(name, "othermaker-aaaa", counting(calls));
  auto rebuilt = cachedFixture(name, "maker-bbbb", counting(calls));
  ASSERT_TRUE(old.ok() && other.ok() && rebuilt.ok());
  EXPECT_EQ(calls, 3);
  EXPECT_NE(*old, *rebuilt);
  EXPECT_FALSE(fs::exists(*old)) << "a stale fixture is never reused, nor kept";
  EXPECT_TRUE(fs::exists(*other / "made.txt")) << "another maker's fixture is not this one's to drop";
  EXPECT_TRUE(fs::exists(*rebuilt / "made.txt"));
  fs::remove_all(*other);
  fs::remove_all(*rebuilt);
}

TEST(FileKey, ChangesWithTheContents) {
  const fs::path f = testOutputDir() / "exe";
  std::ofstream(f) << "build 1";
  const std::string one = fileKey(f);
  std::ofstream(f) << "build 2";
  EXPECT_NE(fileKey(f), one);
  EXPECT_EQ(fileKey(testOutputDir() / "missing"), "missing");
  EXPECT_EQ(programKey().rfind("test_support_tests-", 0), 0u) << programKey();
  EXPECT_EQ(vegstreamKey(), programKey() + fileKey(VEGSTREAM_EXE)) << "both builds name a command-line fixture";
}

}  // namespace
}  // namespace vegstream::testing
