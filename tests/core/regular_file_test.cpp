// The checked opener (core/regular_file.h) against what a file system can hold where a file
// should be: a regular file is read whole; a directory, a FIFO, a link to /dev/zero, a socket's
// place, a file past its ceiling are each one line naming the path, in milliseconds.

#include "core/regular_file.h"

#include <chrono>
#include <fstream>

#include <gtest/gtest.h>
#include <sys/stat.h>

#include "core/text_file.h"
#include "tests/support/test_dirs.h"

namespace vegstream {
namespace {
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

fs::path freshDir(const std::string& name) {
  fs::path dir = testing::testOutputDir() / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

TEST(RegularFile, ReadsARegularFileWhole) {
  const fs::path f = freshDir("rf_ok") / "a.json";
  std::ofstream(f, std::ios::binary) << std::string("{\"a\": 1}\n\0x", 11);
  auto bytes = readRegularFileBytes(f, kJsonFileCeiling);
  ASSERT_TRUE(bytes.ok()) << bytes.error().message;
  EXPECT_EQ(bytes->size(), 11u);
  auto text = readTextFile(f);
  ASSERT_TRUE(text.ok());
  EXPECT_EQ(*text, std::string("{\"a\": 1}\n\0x", 11));
}

TEST(RegularFile, MissingIsNotFoundWithTheHint) {
  auto r = readRegularFile(freshDir("rf_missing") / "none.json", kJsonFileCeiling, "no such species catalog");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().kind, ErrorKind::NotFound);
  EXPECT_NE(r.error().message.find("none.json: no such species catalog"), std::string::npos) << r.error().message;
}

TEST(RegularFile, ADirectoryIsRefusedNotReadAsEmpty) {
  const fs::path d = freshDir("rf_dir") / "dataset.json";
  fs::create_directories(d);
  auto r = readRegularFile(d, kDatasetJsonCeiling);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().kind, ErrorKind::InvalidInput);
  EXPECT_NE(r.error().message.find("is a directory"), std::string::npos) << r.error().message;
  EXPECT_NE(r.error().message.find("dataset.json"), std::string::npos) << r.error().message;
}

TEST(RegularFile, AFifoIsRefusedAtOnceNotWaitedOn) {
  const fs::path f = freshDir("rf_fifo") / "dataset.json";
  ASSERT_EQ(::mkfifo(f.c_str(), 0600), 0);
  const auto t0 = Clock::now();
  auto r = readRegularFile(f, kDatasetJsonCeiling);  // no writer ever opens it: open() would block
  EXPECT_LT(secondsSince(t0), 2.0);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().kind, ErrorKind::InvalidInput);
  EXPECT_NE(r.error().message.find("FIFO"), std::string::npos) << r.error().message;
  auto head = readRegularFileHead(f, 16);
  ASSERT_FALSE(head.ok());
  EXPECT_NE(head.error().message.find("FIFO"), std::string::npos) << head.error().message;
}

TEST(RegularFile, ALinkToDevZeroIsRefusedNotReadUntilMemoryRunsOut) {
  const fs::path f = freshDir("rf_zero") / "1608.png";
  fs::create_symlink("/dev/zero", f);
  const auto t0 = Clock::now();
  auto r = readRegularFileBytes(f, kTileFileCeiling);
  EXPECT_LT(secondsSince(t0), 2.0);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().kind, ErrorKind::InvalidInput);
  EXPECT_NE(r.error().message.find("is a device"), std::string::npos) << r.error().message;
}

TEST(RegularFile, AFilePastItsCeilingIsRefusedBeforeReading) {
  const fs::path f = freshDir("rf_big") / "dataset.json";
  { std::ofstream(f) << "{}"; }
  fs::resize_file(f, kDatasetJsonCeiling.maxBytes + 1);  // sparse: no disk, one byte too many
  const auto t0 = Clock::now();
  auto r = readRegularFile(f, kDatasetJsonCeiling);
  EXPECT_LT(secondsSince(t0), 2.0);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().kind, ErrorKind::InvalidInput);
  EXPECT_NE(r.error().message.find("a dataset.json is at most 4194304 bytes"), std::string::npos) << r.error().message;
  fs::resize_file(f, kDatasetJsonCeiling.maxBytes);  // exactly the ceiling is fine
  EXPECT_TRUE(readRegularFile(f, kDatasetJsonCeiling).ok());
}

TEST(RegularFile, TheHeadOfALargeFileIsReadWithoutItsCeiling) {
  const fs::path f = freshDir("rf_head") / "big.mbtiles";
  { std::ofstream(f) << "SQLite format 3"; }
  fs::resize_file(f, 200 * kMiB);
  auto head = readRegularFileHead(f, 16);
  ASSERT_TRUE(head.ok()) << head.error().message;
  EXPECT_EQ(head->size(), 16u);
  EXPECT_EQ(head->rfind("SQLite format 3", 0), 0u);
}

}  // namespace
}  // namespace vegstream
