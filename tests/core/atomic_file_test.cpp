#include "core/atomic_file.h"

#include <fstream>

#include <gtest/gtest.h>

#include "tests/support/test_dirs.h"

namespace vegstream {
namespace {
namespace fs = std::filesystem;

// `name`, empty, in the running test's own directory.
fs::path freshDir(const std::string& name) {
  fs::path dir = testing::testOutputDir() / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(AtomicFile, RenamesOnlyWhenComplete) {
  const fs::path dir = freshDir("atomic_ok");
  const fs::path target = dir / "out.txt";
  Status s = writeFileAtomically(target, [](const fs::path& tmp) -> Status {
    std::ofstream(tmp) << "hello";
    return {};
  });
  ASSERT_TRUE(s.ok());
  std::ifstream in(target);
  std::string text;
  in >> text;
  EXPECT_EQ(text, "hello");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

TEST(AtomicFile, FailedWriterLeavesNothing) {
  const fs::path dir = freshDir("atomic_fail");
  Status s = writeFileAtomically(dir / "out.txt", [](const fs::path& tmp) -> Status {
    std::ofstream(tmp) << "partial";
    return makeError(ErrorKind::Io, "simulated failure");
  });
  EXPECT_FALSE(s.ok());
  EXPECT_TRUE(fs::is_empty(dir));
}

TEST(AtomicFile, DirectoryRefusesNonEmptyTargetAndCleansUp) {
  const fs::path dir = freshDir("atomic_dir");
  std::ofstream(dir / "keep.txt") << "user data";
  Status s = writeDirectoryAtomically(dir, [](const fs::path&) -> Status { return {}; });
  EXPECT_FALSE(s.ok());
  EXPECT_TRUE(fs::exists(dir / "keep.txt"));

  const fs::path out = testing::testOutputDir() / "atomic_dir_new";
  fs::remove_all(out);
  Status bad = writeDirectoryAtomically(out, [](const fs::path& tmp) -> Status {
    std::ofstream(tmp / "half.txt") << "x";
    return makeError(ErrorKind::InvalidInput, "bad");
  });
  EXPECT_FALSE(bad.ok());
  EXPECT_FALSE(fs::exists(out));
  Status good = writeDirectoryAtomically(out, [](const fs::path& tmp) -> Status {
    std::ofstream(tmp / "a.txt") << "x";
    return {};
  });
  EXPECT_TRUE(good.ok());
  EXPECT_TRUE(fs::exists(out / "a.txt"));
}

}  // namespace
}  // namespace vegstream
