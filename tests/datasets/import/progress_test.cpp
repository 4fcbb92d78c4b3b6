// The progress reporter's plain-line mode (what logs and CI see) and its summary line.

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "datasets/progress.h"
#include "tests/support/test_dirs.h"

namespace vegstream::datasets {
namespace {

TEST(Progress, PlainLinesAndSummaryCountTilesAndBytes) {
  const auto path = vegstream::testing::testOutputDir() / "progress.txt";
  std::filesystem::create_directories(path.parent_path());
  std::FILE* f = std::fopen(path.c_str(), "w");
  ASSERT_NE(f, nullptr);
  std::string summary;
  {
    ProgressReporter p("import", f, 0);
    p.addTotal(3);
    p.stage("zoom 12");
    for (int i = 0; i < 3; ++i) p.tileDone(1024 * 1024);
    summary = p.finish();
    EXPECT_EQ(p.tilesDone(), 3u);
    EXPECT_EQ(p.bytesWritten(), 3u * 1024 * 1024);
  }
  std::fclose(f);
  std::stringstream ss;
  ss << std::ifstream(path).rdbuf();
  EXPECT_NE(ss.str().find("import zoom 12: 0/3 tiles"), std::string::npos) << ss.str();
  EXPECT_EQ(ss.str().find('\r'), std::string::npos);  // no bar redraws off a terminal
  EXPECT_NE(summary.find("3 tiles, 3.0 MB"), std::string::npos) << summary;
}

TEST(Progress, CallbackSeesDoneAndTotal) {
  uint64_t lastDone = 0, lastTotal = 0;
  CallbackProgress p([&](uint64_t d, uint64_t t) {
    lastDone = d;
    lastTotal = t;
  });
  p.addTotal(5);
  p.tileDone(10);
  p.tileDone(10);
  EXPECT_EQ(lastDone, 2u);
  EXPECT_EQ(lastTotal, 5u);
}

}  // namespace
}  // namespace vegstream::datasets
