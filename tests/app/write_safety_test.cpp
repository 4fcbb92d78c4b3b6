// Issue 42, items 4 and 8, through the real executable: a full disk (RLIMIT_FSIZE) leaves the
// user's earlier output byte-identical, exit 1, one line naming the file and the reason, no
// temporary; a second import to the same --out is refused while one runs; SIGKILL at seeded
// moments of an import leaves a whole dataset or none, and the next run cleans up after it; of a
// snapshot, the earlier still or the new one whole.

#include <chrono>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/file_lock.h"
#include "tests/app/record_test_data.h"
#include "tests/support/run_command.h"
#include "tests/support/spawn_command.h"
#include "tests/support/test_dirs.h"

namespace vegstream::testing {
namespace {
namespace fs = std::filesystem;

const std::string kSrtm = std::string(VEGSTREAM_DATASETS_DIR) + "/zion/srtm.tif";

std::string bytesOf(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Entries of `dir` (names) that a writer left under a temporary or lock name.
std::vector<std::string> leftovers(const fs::path& dir) {
  std::vector<std::string> found;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.find(".tmp-") != std::string::npos || name.find(".partial") != std::string::npos ||
        name.ends_with(".lock"))
      found.push_back(fs::relative(it->path(), dir).string());
  }
  return found;
}

// Relative paths of the files under `dir`, sorted.
std::set<std::string> filesUnder(const fs::path& dir) {
  std::set<std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) files.insert(fs::relative(e.path(), dir).generic_string());
  return files;
}

// Lines of `text` containing `needle`.
int linesWith(const std::string& text, const std::string& needle) {
  int n = 0;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) n += line.find(needle) != std::string::npos;
  return n;
}

std::vector<std::string> importArgs(const fs::path& out) { return {"import", "--dem", kSrtm, "--out", out.string()}; }

std::vector<std::string> snapshotArgs(const fs::path& still) {
  return {"snapshot", recordDataset().string(), "--lat", "46.55", "--lon", "7.95", "--alt", "30", "--heading", "0",
          "--pitch", "-20", "--size", "160x90", "--out", still.string()};
}

TEST(FullDisk, SnapshotKeepsTheEarlierStillAndSaysWhy) {
  const fs::path dir = testOutputDir() / "stills";
  fs::create_directories(dir);
  const fs::path still = dir / "still.png", sidecar = dir / "still.json";
  std::ofstream(still, std::ios::binary) << "the user's earlier still";
  std::ofstream(sidecar, std::ios::binary) << "{\"earlier\": true}\n";
  const auto r = runVegstreamLimited(snapshotArgs(still), 2 * 1024, testOutputDir() / "capture");
  EXPECT_EQ(r.exitCode, 1) << r.err;
  EXPECT_EQ(linesWith(r.err, "file too large"), 1) << r.err;
  EXPECT_EQ(linesWith(r.err, still.string()), 1) << r.err;
  EXPECT_EQ(r.err.find("snapshot written"), std::string::npos) << r.err;
  EXPECT_EQ(bytesOf(still), "the user's earlier still");
  EXPECT_EQ(bytesOf(sidecar), "{\"earlier\": true}\n");
  EXPECT_EQ(leftovers(dir), std::vector<std::string>{});
}

TEST(FullDisk, ImportSaysWhyNotCorruptAndLeavesNothing) {
  const fs::path parent = testOutputDir() / "imports";
  fs::create_directories(parent);
  const fs::path out = parent / "zion";
  const auto r = runVegstreamLimited(importArgs(out), 4 * 1024, testOutputDir() / "capture");
  EXPECT_EQ(r.exitCode, 1) << r.err;
  EXPECT_EQ(linesWith(r.err, "file too large"), 1) << r.err;
  EXPECT_EQ(r.err.find("corrupt"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
  EXPECT_EQ(leftovers(parent), std::vector<std::string>{});
}

TEST(FullDisk, JpegImageryImportEndsWithOneLineNotLibjpegsExit) {
  const fs::path parent = testOutputDir() / "imports";
  fs::create_directories(parent);
  const fs::path out = parent / "zion-jpeg";
  const std::string z = std::string(VEGSTREAM_DATASETS_DIR) + "/zion/";
  const auto r = runVegstreamLimited({"import", "--dem", kSrtm, "--imagery-bands",
                                      z + "landsat_b4.tif," + z + "landsat_b3.tif," + z + "landsat_b2.tif",
                                      "--imagery-format", "jpeg", "--out", out.string()},
                                     24 * 1024, testOutputDir() / "capture");
  EXPECT_EQ(r.exitCode, 1) << r.err;
  EXPECT_EQ(linesWith(r.err, "file too large"), 1) << r.err;
  EXPECT_EQ(r.err.find("Output file write error"), std::string::npos) << r.err;  // libjpeg's own exit
  EXPECT_FALSE(fs::exists(out));
  EXPECT_EQ(leftovers(parent), std::vector<std::string>{});
}

TEST(ImportLock, ASecondImportToTheSameOutIsRefused) {
  const fs::path parent = testOutputDir();
  const fs::path out = parent / "zion";
  {
    // Another import holds the lock (as runImport does, through the same file).
    auto held = FileLock::acquire(parent / ".zion.lock", "--out " + out.string());
    ASSERT_TRUE(held) << held.error().message;
    const auto r = runVegstream("import --dem '" + kSrtm + "' --out '" + out.string() + "'");
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_EQ(countLines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("in use by another vegstream process"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
  }
  const auto r = runVegstream("import --dem '" + kSrtm + "' --out '" + out.string() + "'");
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(fs::exists(out / "dataset.json"));
  EXPECT_EQ(leftovers(parent), std::vector<std::string>{});
}

// SIGKILL at 10 seeded moments across an import: afterwards --out is absent or a whole dataset
// (the reference's files, `info` reads it); the next run (with --resume or without, in turn)
// completes, and nothing of the killed run is left beside --out.
TEST(KillSafety, ImportKilledAtTenMomentsLeavesAWholeDatasetOrNone) {
  const fs::path parent = testOutputDir();
  const fs::path reference = parent / "reference", out = parent / "zion";
  const auto start = std::chrono::steady_clock::now();
  ASSERT_EQ(waitExit(spawnVegstream(importArgs(reference))), 0);
  const auto fullRun = std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now() - start);
  const std::set<std::string> expected = filesUnder(reference);
  ASSERT_GT(expected.size(), 3u);
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> moment(0.0, 1.1);
  for (int k = 0; k < 10; ++k) {
    const auto delay = std::chrono::microseconds(static_cast<int64_t>(moment(rng) * static_cast<double>(fullRun.count())));
    SCOPED_TRACE("kill " + std::to_string(k) + " after " + std::to_string(delay.count() / 1000) + " ms");
    const int code = runVegstreamKilledAfter(importArgs(out), delay);
    EXPECT_TRUE(code == 0 || code == 128 + SIGKILL) << code;
    if (fs::exists(out)) {
      EXPECT_EQ(filesUnder(out), expected);
      EXPECT_EQ(runVegstream("info '" + out.string() + "'").exitCode, 0);
      // Killed after the rename, before the lock's release: its file stays (free, as the kernel
      // dropped the lock) until the next import to this --out takes it over.
      fs::remove(parent / ".zion.lock");
    } else {
      std::vector<std::string> next = importArgs(out);
      if (k % 2 == 0) next.push_back("--resume");
      ASSERT_EQ(waitExit(spawnVegstream(next)), 0);
      EXPECT_EQ(filesUnder(out), expected);
    }
    EXPECT_EQ(leftovers(parent), std::vector<std::string>{});
    fs::remove_all(out);
  }
}

// SIGKILL at 5 seeded moments of a snapshot over an earlier still: the still and its sidecar are
// each the earlier file or the new one whole (runs are identical on one driver); the next
// complete run removes the temporaries the killed ones left.
TEST(KillSafety, SnapshotKilledLeavesTheEarlierStillOrTheNewOne) {
  const fs::path dir = testOutputDir() / "stills";
  fs::create_directories(dir);
  const fs::path still = dir / "still.png", sidecar = dir / "still.json";
  const auto start = std::chrono::steady_clock::now();
  ASSERT_EQ(waitExit(spawnVegstream(snapshotArgs(still))), 0);
  const auto fullRun = std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now() - start);
  const std::string newStill = bytesOf(still), newSidecar = bytesOf(sidecar);
  ASSERT_GT(newStill.size(), 100u);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> moment(0.0, 1.1);
  for (int k = 0; k < 5; ++k) {
    std::ofstream(still, std::ios::binary) << "earlier still";
    std::ofstream(sidecar, std::ios::binary) << "earlier sidecar";
    const auto delay = std::chrono::microseconds(static_cast<int64_t>(moment(rng) * static_cast<double>(fullRun.count())));
    SCOPED_TRACE("kill " + std::to_string(k) + " after " + std::to_string(delay.count() / 1000) + " ms");
    const int code = runVegstreamKilledAfter(snapshotArgs(still), delay);
    EXPECT_TRUE(code == 0 || code == 128 + SIGKILL) << code;
    const std::string s = bytesOf(still), j = bytesOf(sidecar);
    EXPECT_TRUE(s == "earlier still" || s == newStill) << s.size() << " bytes";
    EXPECT_TRUE(j == "earlier sidecar" || j == newSidecar) << j;
  }
  ASSERT_EQ(waitExit(spawnVegstream(snapshotArgs(still))), 0);
  EXPECT_EQ(bytesOf(still), newStill);
  EXPECT_EQ(leftovers(dir), std::vector<std::string>{});
}

}  // namespace
}  // namespace vegstream::testing
