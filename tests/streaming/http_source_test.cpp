// The HTTP source against Debian's nginx on loopback: the static server DESIGN.md promises a
// dataset directory works with, served as it is.

#include <gtest/gtest.h>

#include <chrono>
#include <iostream>
#include <set>
#include <thread>

#include "streaming/http_tile_source.h"
#include "streaming/open_tile_source.h"
#include "tests/streaming/http_test_dataset.h"
#include "tests/support/nginx_server.h"

namespace vegstream::streaming {
namespace {
using testing::fileBytes;
using testing::NginxServer;
using testing::Results;

class NginxSource : public testing::HttpDataset {
 protected:
  static void SetUpTestSuite() {
    HttpDataset::SetUpTestSuite();
    auto server = NginxServer::start(work(), work() / "nginx");
    if (!server.ok()) {
      setupError_ += server.error().message;
      return;
    }
    nginx_ = std::move(*server).release();
  }
  static void TearDownTestSuite() {
    delete nginx_;
    HttpDataset::TearDownTestSuite();
  }
  static std::string datasetUrl() { return nginx_->baseUrl() + "/synthetic"; }
  static std::shared_ptr<HttpTileSource> open(int maxInFlight = 8) {
    HttpSourceOptions o;
    o.baseUrl = datasetUrl();
    o.maxInFlight = maxInFlight;
    auto s = HttpTileSource::create(o);
    EXPECT_TRUE(s.ok()) << s.error().message;
    return *s;
  }
  // nginx writes a request's log line just after its answer: wait up to a second for `atLeast`.
  static size_t logLinesFor(const std::string& uri, size_t atLeast = 1) {
    size_t n = 0;
    for (int i = 0; i < 100; ++i) {
      n = 0;
      for (const auto& l : nginx_->accessLog()) n += l.uri == uri;
      if (n >= atLeast) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return n;
  }
  static std::vector<testing::NginxLogLine> logOfAtLeast(size_t lines) {
    auto log = nginx_->accessLog();
    for (int i = 0; i < 100 && log.size() < lines; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
      log = nginx_->accessLog();
    }
    return log;
  }
  static inline NginxServer* nginx_ = nullptr;
};

TEST_F(NginxSource, EveryTileIsByteIdenticalToItsFile) {
  ASSERT_GE(tiles().size(), 10u);
  auto source = open();
  // Several rounds, for a throughput figure worth printing; every answer is checked.
  constexpr int kRounds = 10;
  Results results;
  const auto t0 = std::chrono::steady_clock::now();
  RequestId id = 1;
  for (int round = 0; round < kRounds; ++round)
    for (const auto& t : tiles()) source->start(id++, t, results.callback());
  const size_t n = tiles().size() * kRounds;
  ASSERT_TRUE(results.waitFor(n));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  size_t identical = 0;
  uint64_t bytes = 0;
  for (const auto& r : results.take()) {
    const std::string& path = tiles()[(r.id - 1) % tiles().size()];
    ASSERT_EQ(r.outcome, FetchOutcome::Ok) << path << ": " << r.message;
    identical += r.bytes == fileBytes(dir() / path);
    bytes += r.bytes.size();
  }
  EXPECT_EQ(identical, n);
  EXPECT_TRUE(results.eachOnce(1, n));
  const SourceCounters c = source->counters();
  EXPECT_EQ(c.requestsStarted, n);
  EXPECT_EQ(c.requestsCompleted, n);
  EXPECT_EQ(c.retries, 0u);
  EXPECT_EQ(c.bytesRead, bytes);
  EXPECT_EQ(testing::inFlightAfterCallbacks(*source), 0u);
  EXPECT_LE(source->transportStats().connectionsOpened, 8u) << "one connection per transfer slot at most";
  std::cout << "nginx loopback: " << n << " tiles, " << bytes / 1024 << " KiB in " << seconds
            << " s = " << static_cast<double>(n) / seconds << " tiles/s, " << static_cast<double>(bytes) / seconds / 1e6
            << " MB/s (maxInFlight 8)\n";
}

TEST_F(NginxSource, MetaOverHttpEqualsTheDirectorysMeta) {
  auto source = open();
  auto http = readMetaFrom(*source);
  ASSERT_TRUE(http.ok()) << http.error().message;
  auto local = datasets::readDatasetMeta(dir());
  ASSERT_TRUE(local.ok());
  EXPECT_EQ(http->name, local->name);
  EXPECT_EQ(http->minZoom, local->minZoom);
  EXPECT_EQ(http->maxZoom, local->maxZoom);
  EXPECT_EQ(http->bounds.westDeg, local->bounds.westDeg);
  EXPECT_EQ(http->bounds.northDeg, local->bounds.northDeg);
  EXPECT_EQ(http->minHeightM, local->minHeightM);
  EXPECT_EQ(http->maxHeightM, local->maxHeightM);
  EXPECT_EQ(http->elevationEncoding, local->elevationEncoding);
  EXPECT_EQ(http->imagery, local->imagery);
  EXPECT_EQ(http->elevationTiles, local->elevationTiles);
  EXPECT_EQ(http->imageryTiles, local->imageryTiles);
  EXPECT_EQ(http->bytes, local->bytes);
  EXPECT_EQ(http->sources.size(), local->sources.size());
  EXPECT_EQ(source->counters().requestsStarted, 0u) << "readText is not a tile request";
}

TEST_F(NginxSource, MissingTileIsMissingAfterOneAttempt) {
  auto source = open();
  Results results;
  source->start(7, "elevation/3/0/0.png", results.callback());
  ASSERT_TRUE(results.waitFor(1));
  const auto r = results.take().at(0);
  EXPECT_EQ(r.outcome, FetchOutcome::Missing);
  EXPECT_EQ(r.attempts, 1);
  EXPECT_NE(r.message.find("/synthetic/elevation/3/0/0.png"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("404"), std::string::npos) << r.message;
  EXPECT_EQ(logLinesFor("/synthetic/elevation/3/0/0.png"), 1u) << "the server saw no retry";
  EXPECT_EQ(source->counters().requestsMissing, 1u);
  EXPECT_EQ(source->counters().retries, 0u);
}

TEST_F(NginxSource, SequentialTilesReuseOneConnection) {
  auto source = open();
  const size_t before = nginx_->accessLog().size();
  constexpr size_t kFetches = 50;
  Results results;
  for (size_t i = 0; i < kFetches; ++i) {
    source->start(i + 1, tiles()[i % tiles().size()], results.callback());
    ASSERT_TRUE(results.waitFor(i + 1));
  }
  EXPECT_EQ(source->transportStats().connectionsOpened, 1u);
  const auto log = logOfAtLeast(before + kFetches);
  ASSERT_EQ(log.size(), before + kFetches);
  std::set<uint64_t> connections;
  for (size_t i = before; i < log.size(); ++i) connections.insert(log[i].connection);
  EXPECT_EQ(connections.size(), 1u) << "nginx saw " << connections.size() << " connections for " << kFetches
                                    << " sequential tiles";
}

TEST_F(NginxSource, DestroyingMidFlightCallsEachBackOnce) {
  Results results;
  const size_t n = tiles().size() * 3;
  const auto t0 = std::chrono::steady_clock::now();
  {
    auto source = open(4);
    for (size_t i = 0; i < n; ++i) source->start(i + 1, tiles()[i % tiles().size()], results.callback());
  }  // destroyed with most of them queued or running
  EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(2));
  EXPECT_TRUE(results.eachOnce(1, n));
  for (const auto& r : results.take())
    EXPECT_TRUE(r.outcome == FetchOutcome::Ok || r.outcome == FetchOutcome::Cancelled) << r.message;
}

TEST_F(NginxSource, OpenTileSourcePicksHttpOrDirectory) {
  OpenSourceOptions o;
  auto http = openTileSource(datasetUrl(), o);
  ASSERT_TRUE(http.ok()) << http.error().message;
  EXPECT_NE(dynamic_cast<HttpTileSource*>(http->get()), nullptr);
  auto local = openTileSource(dir().string(), o);
  ASSERT_TRUE(local.ok()) << local.error().message;
  EXPECT_EQ(dynamic_cast<HttpTileSource*>(local->get()), nullptr);
  auto a = readMetaFrom(**http);
  auto b = readMetaFrom(**local);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(a->name, b->name);

  auto bad = openTileSource("http://", o);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().kind, ErrorKind::InvalidInput);
  auto none = openTileSource((work() / "no_such_dir").string(), o);
  ASSERT_FALSE(none.ok());
  EXPECT_EQ(none.error().kind, ErrorKind::NotFound);

  // A server without a dataset there: NotFound naming the URL, after one request.
  auto empty = openTileSource(nginx_->baseUrl() + "/nothing", o);
  ASSERT_TRUE(empty.ok());
  auto meta = readMetaFrom(**empty);
  ASSERT_FALSE(meta.ok());
  EXPECT_EQ(meta.error().kind, ErrorKind::NotFound);
  EXPECT_NE(meta.error().message.find("/nothing/dataset.json"), std::string::npos) << meta.error().message;
  EXPECT_EQ(logLinesFor("/nothing/dataset.json"), 1u);
}

}  // namespace
}  // namespace vegstream::streaming
