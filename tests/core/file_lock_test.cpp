// core/file_lock.h: one holder at a time, across processes; a killed holder's lock is free.

#include "core/file_lock.h"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "tests/support/test_dirs.h"

namespace vegstream {
namespace {
namespace fs = std::filesystem;

TEST(FileLock, ASecondHolderIsRefusedUntilTheFirstReleases) {
  const fs::path dir = testing::testOutputDir();
  const fs::path file = dir / ".out.lock";
  {
    auto first = FileLock::acquire(file, "--out out");
    ASSERT_TRUE(first) << first.error().message;
    auto second = FileLock::acquire(file, "--out out");
    ASSERT_FALSE(second);
    EXPECT_EQ(second.error().kind, ErrorKind::InvalidInput);
    EXPECT_NE(second.error().message.find("--out out is in use by another vegstream process (PID " +
                                          std::to_string(::getpid())),
              std::string::npos)
        << second.error().message;
  }
  EXPECT_FALSE(fs::exists(file)) << "a released lock leaves no file";
  auto again = FileLock::acquire(file, "--out out");
  EXPECT_TRUE(again);
}

TEST(FileLock, AKilledHoldersLockIsFree) {
  const fs::path file = testing::testOutputDir() / ".killed.lock";
  int ready[2];
  ASSERT_EQ(::pipe(ready), 0);
  const pid_t pid = ::fork();
  if (pid == 0) {
    auto lock = FileLock::acquire(file, "x");
    const char c = lock ? 'y' : 'n';
    if (::write(ready[1], &c, 1) != 1) ::_exit(2);
    ::pause();
    ::_exit(0);
  }
  char c = 0;
  ASSERT_EQ(::read(ready[0], &c, 1), 1);
  ASSERT_EQ(c, 'y');
  EXPECT_FALSE(FileLock::acquire(file, "x")) << "the child holds it";
  ::kill(pid, SIGKILL);
  ::waitpid(pid, nullptr, 0);
  EXPECT_TRUE(fs::exists(file)) << "a killed holder cannot remove its file";
  auto taken = FileLock::acquire(file, "x");
  EXPECT_TRUE(taken) << "the kernel dropped the killed holder's lock";
  ::close(ready[0]);
  ::close(ready[1]);
}

}  // namespace
}  // namespace vegstream
