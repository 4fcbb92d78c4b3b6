// `vegstream fly URL --http-cache DIR` against a hostile server (issue 42 item 3), as a user runs
// it: for each hostile answer given to a third of the tiles (or to dataset.json), the command
// ends with exit 0 (the bad tiles drawn from their parents) or 2 (one line naming the URL),
// within twice its deadlines, at bounded memory (the child's own peak RSS), and with nothing in
// the cache but whole tiles of the dataset — a later run against the healed server fetches and
// caches those tiles.

#include <gtest/gtest.h>

#include <cstdio>

#include "streaming/disk_tile_cache.h"
#include "tests/streaming/streaming_fixture.h"
#include "tests/support/fault_http_server.h"
#include "tests/support/measured_command.h"

namespace vegstream::streaming::test {
namespace {
using testing::Fault;
using testing::FaultAction;
using testing::FaultHttpServer;

// --http-timeout-s: one request, all its retries. A loopback server answers a healthy request in
// milliseconds, and the hostile cases wait out deadlines: the 11 cases took 390 s with 4 s on the
// 2-core build machine (ctest -j2), 324 s with 2.5.
constexpr double kHttpTimeoutS = 2.5;
// Stages that may each wait out one request deadline: the ground heights (scene, trees), the
// trees' imagery and NDVI, and the frames' own tiles.
constexpr int kStages = 6;

struct HostileCase {
  const char* name;
  Fault fault;
  bool onDatasetJson = false;  // else every third tile
};

std::vector<uint8_t> bytesOf(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class HostileCli : public ::testing::TestWithParam<HostileCase> {
 protected:
  static void SetUpTestSuite() {
    dataset_ = new fs::path(testTmp("hostile-cli-dataset"));
    auto meta = makeSynthetic(*dataset_);
    if (!meta.ok()) setupError_ = meta.error().message;
    tiles_ = new std::vector<std::string>;
    for (const auto& e : fs::recursive_directory_iterator(*dataset_))
      if (e.is_regular_file() && e.path().filename() != "dataset.json")
        tiles_->push_back(fs::relative(e.path(), *dataset_).generic_string());
    std::sort(tiles_->begin(), tiles_->end());
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dataset_);
    delete dataset_;
    delete tiles_;
  }
  void SetUp() override { ASSERT_TRUE(setupError_.empty()) << setupError_; }

  testing::MeasuredResult fly(const FaultHttpServer& server, const fs::path& cache, const std::string& extra = {}) {
    const fs::path out = testTmp(std::string("hostile-cli-out-") + GetParam().name);
    char timeout[32];
    std::snprintf(timeout, sizeof(timeout), "%.1f", kHttpTimeoutS);
    return testing::runMeasured(std::string(VEGSTREAM_EXE) + " fly " + server.baseUrl() +
                                " --headless --frames 2 --size 160x90 --msaa 1 --http-cache '" + cache.string() +
                                "' --http-timeout-s " + timeout + " --out '" + out.string() + "' " + extra);
  }
  // Every cached file is byte for byte a tile of the dataset; returns how many tiles are cached.
  static size_t expectCacheHoldsOnlyWholeTiles(const fs::path& cache, const FaultHttpServer& server) {
    const std::string host = server.baseUrl().substr(std::string("http://").size());
    size_t files = 0, matched = 0;
    for (const auto& e : fs::recursive_directory_iterator(cache))
      files += e.is_regular_file() && e.path().filename().string().find(".tmp") == std::string::npos;
    for (const auto& t : *tiles_) {
      const fs::path f = cache / DiskTileCache::relativeFileFor(host + "/" + t);
      if (!fs::exists(f)) continue;
      ++matched;
      EXPECT_EQ(bytesOf(f), bytesOf(*dataset_ / t)) << "poisoned: " << t;
    }
    EXPECT_EQ(files, matched) << "a cached file that is no tile of the dataset";
    return matched;
  }
  static inline fs::path* dataset_ = nullptr;
  static inline std::vector<std::string>* tiles_ = nullptr;
  static inline std::string setupError_;
  static inline double healthySeconds_ = -1.0, healthyRssMb_ = -1.0;
};

TEST_P(HostileCli, EndsInTimeAtBoundedMemoryWithNothingPoisoned) {
  const HostileCase& c = GetParam();
  FaultHttpServer server(*dataset_);
  if (healthySeconds_ < 0) {  // the reference: a healthy server, no cache
    const auto healthy = fly(server, testTmp("hostile-cli-healthy-cache"));
    ASSERT_EQ(healthy.exitCode, 0) << healthy.err;
    healthySeconds_ = healthy.seconds;
    healthyRssMb_ = healthy.maxRssMb;
    std::printf("[ healthy ] %.1f s, %.0f MB\n", healthySeconds_, healthyRssMb_);
  }
  std::vector<std::string> faulted;
  if (c.onDatasetJson) {
    server.scheduleForPath("dataset.json", std::vector<Fault>(8, c.fault));
  } else {
    for (size_t i = 0; i < tiles_->size(); i += 3) {
      server.scheduleForPath((*tiles_)[i], std::vector<Fault>(200, c.fault));
      faulted.push_back((*tiles_)[i]);
    }
  }
  const fs::path cache = testTmp(std::string("hostile-cli-cache-") + c.name);
  const auto r = fly(server, cache);
  std::printf("[ %s ] exit %d, %.1f s, %.0f MB, %llu bytes sent\n", c.name, r.exitCode, r.seconds, r.maxRssMb,
              static_cast<unsigned long long>(server.bytesSent()));
  EXPECT_TRUE(r.exitCode == 0 || r.exitCode == 2) << r.exitCode << ": " << r.err;
  if (r.exitCode == 2) {
    EXPECT_EQ(testing::countLines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(server.baseUrl()), std::string::npos) << r.err;
  }
  EXPECT_EQ(r.exitCode, c.onDatasetJson ? 2 : 0)
      << (c.onDatasetJson ? "dataset.json is not delivered: " : "a third of the tiles failing is no reason to stop: ")
      << r.err;
  EXPECT_LT(r.seconds, healthySeconds_ + 2.0 * kStages * kHttpTimeoutS);
  EXPECT_LT(r.maxRssMb, healthyRssMb_ + 256.0) << "the body caps (16 MiB a transfer) bound memory";
  if (fs::exists(cache)) expectCacheHoldsOnlyWholeTiles(cache, server);

  // The server heals: the same cache, a run that succeeds, and the tiles that were bad are
  // fetched whole and cached now.
  server.clearFaults();
  const auto again = fly(server, cache);
  ASSERT_EQ(again.exitCode, 0) << again.err;
  EXPECT_GT(expectCacheHoldsOnlyWholeTiles(cache, server), 0u);
  if (!faulted.empty()) {
    const std::string host = server.baseUrl().substr(std::string("http://").size());
    size_t healed = 0;
    for (const auto& t : faulted) healed += fs::exists(cache / DiskTileCache::relativeFileFor(host + "/" + t));
    EXPECT_GT(healed, 0u) << "the tiles that failed are fetched and cached once the server heals";
  }
}

INSTANTIATE_TEST_SUITE_P(
    Hostile, HostileCli,
    ::testing::Values(HostileCase{"html", {FaultAction::HtmlPage}}, HostileCase{"html_as_png", {FaultAction::HtmlAsImage}},
                      HostileCase{"endless", {FaultAction::EndlessBody}}, HostileCase{"huge_length", {FaultAction::HugeLength}},
                      HostileCase{"slowloris", {FaultAction::Slowloris}}, HostileCase{"stall", {FaultAction::Stall}},
                      HostileCase{"redirect_file", {FaultAction::Redirect, 0, "file:///etc/passwd"}},
                      HostileCase{"redirect_ftp", {FaultAction::Redirect, 0, "ftp://127.0.0.1/tile.png"}},
                      HostileCase{"redirect_other_host", {FaultAction::Redirect, 0, "http://localhost:1/tile.png"}},
                      HostileCase{"dataset_json_endless", {FaultAction::EndlessBody}, true},
                      HostileCase{"dataset_json_html_redirect", {FaultAction::Redirect, 0, "ftp://127.0.0.1/x"}, true}),
    [](const ::testing::TestParamInfo<HostileCase>& i) { return std::string(i.param.name); });

}  // namespace
}  // namespace vegstream::streaming::test
