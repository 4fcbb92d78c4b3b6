// Checked writes under a failing disk (core/checked_write.h, core/atomic_file.h): a child
// process with a small RLIMIT_FSIZE (SIGXFSZ ignored, so write(2) returns EFBIG as a full disk
// returns ENOSPC) replaces a file; the old file must stay byte-identical, the error must be one
// line naming the file and the reason, and no temporary may be left. Also the staged pair and
// the removal of temporaries that a killed process left.

#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <functional>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/atomic_file.h"
#include "core/checked_write.h"
#include "tests/support/test_dirs.h"

namespace vegstream {
namespace {
namespace fs = std::filesystem;

fs::path freshDir(const std::string& name) {
  fs::path dir = testing::testOutputDir() / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string readBytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

size_t entries(const fs::path& dir) {
  return static_cast<size_t>(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

// Runs `body` in a forked child limited to `maxBytes` per file; returns the child's exit code
// and the message it wrote to the pipe.
std::pair<int, std::string> inLimitedChild(rlim_t maxBytes, const std::function<std::string()>& body) {
  int fds[2];
  EXPECT_EQ(::pipe(fds), 0);
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(fds[0]);
    ::signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{maxBytes, maxBytes};
    if (::setrlimit(RLIMIT_FSIZE, &limit) != 0) ::_exit(3);
    const std::string message = body();
    if (::write(fds[1], message.data(), message.size()) < 0) ::_exit(4);
    ::_exit(message.empty() ? 0 : 1);
  }
  ::close(fds[1]);
  std::string message;
  char buf[512];
  for (ssize_t n; (n = ::read(fds[0], buf, sizeof buf)) > 0;) message.append(buf, static_cast<size_t>(n));
  ::close(fds[0]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status), message};
}

TEST(WriteFailure, FileSizeLimitLeavesTheOldFileAndNoTemporary) {
  const fs::path dir = freshDir("limit");
  const fs::path target = dir / "still.png";
  const std::string old = "the user's earlier still";
  ASSERT_TRUE(writeTextAtomically(target, old).ok());
  const auto [code, message] = inLimitedChild(4096, [&] {
    const std::vector<uint8_t> big(64 * 1024, 0x5a);
    const Status s = writeBytesAtomically(target, big);
    return s ? std::string() : s.error().message;
  });
  EXPECT_EQ(code, 1) << message;
  EXPECT_EQ(readBytes(target), old);
  EXPECT_EQ(entries(dir), 1u) << "a temporary was left beside " << target;
  EXPECT_NE(message.find(target.string()), std::string::npos) << message;
  EXPECT_NE(message.find("file too large"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

TEST(WriteFailure, ReasonsAreTheOperatingSystems) {
  EXPECT_EQ(ioReason(ENOSPC), "disk full");
  EXPECT_NE(ioReason(EFBIG).find("file too large"), std::string::npos);
  EXPECT_EQ(ioReason(EACCES), std::string(std::strerror(EACCES)));
  const Error e = writeError("/x/y.png", ENOSPC);
  EXPECT_EQ(e.kind, ErrorKind::Io);
  EXPECT_EQ(e.message, "cannot write '/x/y.png': disk full");
}

TEST(WriteFailure, AnUnwritableTargetNamesTheFileAndTheReason) {
  const fs::path dir = freshDir("unwritable");
  fs::create_directories(dir / "a_directory");  // a file cannot replace it
  const Status s = writeTextAtomically(dir / "a_directory", "x");
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("a_directory"), std::string::npos) << s.error().message;
  EXPECT_TRUE(fs::is_directory(dir / "a_directory"));
  EXPECT_EQ(entries(dir), 1u);
}

TEST(StagedFile, NothingIsRenamedBeforeEveryPartIsWritten) {
  const fs::path dir = freshDir("staged");
  ASSERT_TRUE(writeTextAtomically(dir / "a.png", "old a").ok());
  ASSERT_TRUE(writeTextAtomically(dir / "a.json", "old json").ok());
  const auto [code, message] = inLimitedChild(4096, [&] {
    const std::vector<uint8_t> small{1, 2, 3}, big(64 * 1024, 7);
    auto a = StagedFile::stage(dir / "a.png", small);
    if (!a) return std::string("staging a small file failed: ") + a.error().message;
    auto b = StagedFile::stage(dir / "a.json", big);
    return b ? std::string("a file over the limit was staged") : b.error().message;
  });
  EXPECT_EQ(code, 1);
  EXPECT_NE(message.find("file too large"), std::string::npos) << message;
  EXPECT_EQ(readBytes(dir / "a.png"), "old a");
  EXPECT_EQ(readBytes(dir / "a.json"), "old json");
  EXPECT_EQ(entries(dir), 2u);

  const std::vector<uint8_t> bytes{'n', 'e', 'w'};
  auto a = StagedFile::stage(dir / "a.png", bytes);
  ASSERT_TRUE(a);
  EXPECT_EQ(entries(dir), 3u);
  ASSERT_TRUE(a->commit().ok());
  EXPECT_EQ(readBytes(dir / "a.png"), "new");
  { auto dropped = StagedFile::stage(dir / "a.json", bytes); }
  EXPECT_EQ(readBytes(dir / "a.json"), "old json");
  EXPECT_EQ(entries(dir), 2u);
}

// A PID that ran and is gone (reaped): a killed writer's.
long deadPid() {
  const pid_t pid = ::fork();
  if (pid == 0) ::_exit(0);
  ::waitpid(pid, nullptr, 0);
  return pid;
}

TEST(StaleTemporaries, OnlyThoseOfDeadProcessesAreRemoved) {
  const fs::path dir = freshDir("stale");
  const long dead = deadPid();
  const std::string deadTmp = "out.png.tmp-" + std::to_string(dead) + "-3";
  const std::string liveTmp = "out.png.tmp-" + std::to_string(::getppid()) + "-0";
  const std::string otherTarget = "other.png.tmp-" + std::to_string(dead) + "-1";
  const std::string deadDir = "rec.tmp-" + std::to_string(dead) + "-0";
  for (const std::string& n : {deadTmp, liveTmp, otherTarget}) std::ofstream(dir / n) << "half";
  fs::create_directories(dir / deadDir / "frames");
  long pid = 0;
  EXPECT_TRUE(parseTemporaryName(deadTmp, &pid));
  EXPECT_EQ(pid, dead);
  EXPECT_TRUE(parseTemporaryName("t.gpkg.tmp-12-0.gpkg", &pid));
  EXPECT_FALSE(parseTemporaryName("notes.tmp-draft", &pid));
  EXPECT_FALSE(parseTemporaryName("a.tmp-12-", &pid));

  ASSERT_TRUE(writeTextAtomically(dir / "out.png", "new").ok());
  EXPECT_FALSE(fs::exists(dir / deadTmp));
  EXPECT_TRUE(fs::exists(dir / liveTmp));
  EXPECT_TRUE(fs::exists(dir / otherTarget));  // another target's: left to its own next write
  ASSERT_TRUE(writeDirectoryAtomically(dir / "rec", [](const fs::path&) { return Status{}; }).ok());
  EXPECT_FALSE(fs::exists(dir / deadDir));
  EXPECT_TRUE(fs::is_directory(dir / "rec"));
}

}  // namespace
}  // namespace vegstream
