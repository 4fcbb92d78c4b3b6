// The GDAL importer at scale and over the network (issue 40): a COG read by HTTP range requests
// from nginx on loopback equals the same file read from disk; a 144 Mpx DEM imports within a
// bounded peak memory (getrusage of the import's own process); an import killed with SIGKILL
// leaves no dataset, and --resume finishes it to the same bytes as an uninterrupted one.

#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fcntl.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "datasets/dataset_format.h"
#include "tests/datasets/import/dataset_compare.h"
#include "tests/support/nginx_server.h"
#include "tests/support/run_command.h"
#include "tests/support/test_dirs.h"

extern char** environ;

namespace vegstream::datasets {
namespace {
namespace fs = std::filesystem;
using testing::runCommand;
using testing::runVegstream;

std::string sample(const std::string& rel) { return std::string(VEGSTREAM_DATASETS_DIR) + "/" + rel; }

// Runs vegstream with `args` in a child process; returns its exit code and peak resident set
// (KiB, from wait4's rusage: that process alone).
struct Child {
  pid_t pid = -1;
};

Child spawn(const std::vector<std::string>& args) {
  std::vector<std::string> all{VEGSTREAM_EXE};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  Child c;
  if (posix_spawn(&c.pid, VEGSTREAM_EXE, &actions, nullptr, argv.data(), environ) != 0) c.pid = -1;
  posix_spawn_file_actions_destroy(&actions);
  return c;
}

struct Finished {
  int exitCode = -1;
  long maxRssKiB = 0;
};

Finished waitFor(const Child& c) {
  int status = 0;
  rusage usage{};
  Finished f;
  if (::wait4(c.pid, &status, 0, &usage) != c.pid) return f;
  f.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  f.maxRssKiB = usage.ru_maxrss;
  return f;
}

class GdalImportScale : public ::testing::Test {
 protected:
  void SetUp() override { work_ = testing::testOutputDir(); }
  fs::path work_;
};

TEST_F(GdalImportScale, CogOverHttpEqualsTheFileOnDisk) {
  const fs::path www = work_ / "www";
  fs::create_directories(www);
  const fs::path cog = www / "srtm_cog.tif";
  ASSERT_EQ(runCommand("gdal_translate -q -of COG -co BLOCKSIZE=128 '" + sample("zion/srtm.tif") + "' '" +
                       cog.string() + "'")
                .exitCode,
            0);
  auto server = testing::NginxServer::start(www, work_ / "nginx");
  ASSERT_TRUE(server.ok()) << server.error().message;
  const std::string url = (*server)->baseUrl() + "/srtm_cog.tif";
  const fs::path disk = work_ / "disk", http = work_ / "http";
  auto r = runVegstream("import --dem '" + cog.string() + "' --out '" + disk.string() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  r = runVegstream("import --dem '" + url + "' --out '" + http.string() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto c = test::compareTileTrees(disk, http);
  EXPECT_GT(c.files, 20);
  EXPECT_EQ(c.different, 0) << c.firstDifference;
  // Read by range requests (206), not fetched whole.
  int partial = 0;
  for (const auto& line : (*server)->accessLog()) partial += line.uri == "/srtm_cog.tif" && line.status == 206;
  EXPECT_GT(partial, 0);
  auto meta = readDatasetMeta(http);
  ASSERT_TRUE(meta);
  EXPECT_EQ(meta->sources[0].path, url);

  // A URL that fails: one line naming it, exit 2, nothing left.
  const std::string missing = (*server)->baseUrl() + "/no_such_dem.tif";
  const fs::path none = work_ / "none";
  r = runVegstream("import --dem '" + missing + "' --out '" + none.string() + "'");
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_EQ(testing::countLines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(missing), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(none));
  EXPECT_FALSE(fs::exists(work_ / ".none.partial"));
}

// A 12 090 × 11 882 px DEM (143.7 Mpx, 575 MB as float): the SRTM sample tiled 26 × 26 times
// by a VRT, so it costs no disk. The import must not hold it: peak RSS ≤ 512 MiB.
TEST_F(GdalImportScale, A144MpxDemImportsInBoundedMemory) {
  const int n = 26, w = 465, h = 457;
  const double px = 0.000833333333278;
  const fs::path vrt = work_ / "big.vrt";
  {
    std::ofstream f(vrt);
    f << "<VRTDataset rasterXSize=\"" << n * w << "\" rasterYSize=\"" << n * h << "\">\n"
      << "<SRS>EPSG:4326</SRS><GeoTransform>-118.0, " << px << ", 0, 42.0, 0, " << -px << "</GeoTransform>\n"
      << "<VRTRasterBand dataType=\"Float32\" band=\"1\"><NoDataValue>65535</NoDataValue>\n";
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        f << "<SimpleSource><SourceFilename>" << sample("zion/srtm.tif") << "</SourceFilename><SourceBand>1</SourceBand>"
          << "<SrcRect xOff=\"0\" yOff=\"0\" xSize=\"" << w << "\" ySize=\"" << h << "\"/><DstRect xOff=\"" << i * w
          << "\" yOff=\"" << j * h << "\" xSize=\"" << w << "\" ySize=\"" << h << "\"/></SimpleSource>\n";
    f << "</VRTRasterBand></VRTDataset>\n";
  }
  const fs::path out = work_ / "big";
  const Finished f = waitFor(spawn({"import", "--dem", vrt.string(), "--max-zoom", "9", "--memory-mb", "256",
                                    "--threads", "2", "--out", out.string()}));
  ASSERT_EQ(f.exitCode, 0);
  std::printf("144 Mpx DEM → zoom 9: peak resident %.1f MiB\n", static_cast<double>(f.maxRssKiB) / 1024.0);
  EXPECT_LE(f.maxRssKiB, 512L * 1024L);
  auto meta = readDatasetMeta(out);
  ASSERT_TRUE(meta);
  EXPECT_GT(meta->elevationTiles, 150u);
  EXPECT_NEAR(meta->maxHeightM, 2892.0, 5.0);
}

TEST_F(GdalImportScale, KilledImportLeavesNoDatasetAndResumeFinishesIt) {
  const std::string z = sample("zion/");
  const std::vector<std::string> args{"import", "--dem", z + "srtm.tif", "--imagery-bands",
                                      z + "landsat_b4.tif," + z + "landsat_b3.tif," + z + "landsat_b2.tif",
                                      "--max-zoom", "13", "--threads", "1", "--name", "zion"};
  const fs::path whole = work_ / "whole", killed = work_ / "killed";
  auto all = args;
  all.insert(all.end(), {"--out", whole.string()});
  ASSERT_EQ(waitFor(spawn(all)).exitCode, 0);

  auto first = args;
  first.insert(first.end(), {"--out", killed.string()});
  const Child c = spawn(first);
  ASSERT_GT(c.pid, 0);
  const fs::path journal = work_ / ".killed.partial" / "journal.txt";
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  size_t lines = 0;
  while (lines < 40 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    const std::string text = testing::readWhole(journal);
    lines = static_cast<size_t>(std::count(text.begin(), text.end(), '\n'));
  }
  ::kill(c.pid, SIGKILL);
  waitFor(c);
  ASSERT_GE(lines, 40u) << "the import never got going";
  EXPECT_FALSE(fs::exists(killed / "dataset.json"));
  EXPECT_NE(runVegstream("info '" + killed.string() + "'").exitCode, 0);

  auto resume = first;
  resume.push_back("--resume");
  const auto r = runVegstream([&] {
    std::string s;
    for (size_t i = 0; i < resume.size(); ++i) s += (i ? " '" : "'") + resume[i] + "'";
    return s;
  }());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("already done"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(work_ / ".killed.partial"));
  const auto cmp = test::compareTileTrees(whole, killed);
  EXPECT_GT(cmp.files, 100);
  EXPECT_EQ(cmp.different, 0) << cmp.firstDifference;
  EXPECT_EQ(test::fileBytes(whole / "dataset.json"), test::fileBytes(killed / "dataset.json"));
}

}  // namespace
}  // namespace vegstream::datasets
