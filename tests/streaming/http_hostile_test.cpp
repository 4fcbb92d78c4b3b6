// The HTTP source against a hostile server (issue 42 item 3): error pages sent as tiles, bodies
// without end, a 10 GB Content-Length, bytes trickling (slowloris), stalls and redirects to
// file://, ftp:// and another host. Each ends Ok or Failed within its deadline, with bounded
// memory (the server counts what it sent; the source's cap bounds what it kept), and nothing
// that is not a whole tile of the dataset is ever cached.

#include <gtest/gtest.h>

#include <chrono>

#include "streaming/disk_tile_cache.h"
#include "streaming/http_tile_source.h"
#include "streaming/tile_check.h"
#include "tests/streaming/http_test_dataset.h"
#include "tests/support/fault_http_server.h"

namespace vegstream::streaming {
namespace {
namespace fs = std::filesystem;
using testing::Fault;
using testing::FaultAction;
using testing::FaultHttpServer;
using testing::fileBytes;
using testing::Results;
using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

class HostileServer : public testing::HttpDataset {
 protected:
  void SetUp() override {
    HttpDataset::SetUp();
    if (HasFatalFailure()) return;
    server_ = std::make_unique<FaultHttpServer>(dir());
  }
  HttpSourceOptions options() const {
    HttpSourceOptions o;
    o.baseUrl = server_->baseUrl();
    o.maxInFlight = 4;
    o.backoffBaseMs = 10;
    o.backoffMaxMs = 40;
    o.connectTimeoutMs = 2000;
    o.totalTimeoutMs = 5000;
    o.lowSpeedTimeS = 1;  // a stall or a trickle is given up after 1 s
    o.maxBodyBytes = 1u << 20;
    return o;
  }
  std::shared_ptr<HttpTileSource> open(const HttpSourceOptions& o) const {
    auto s = HttpTileSource::create(o);
    EXPECT_TRUE(s.ok()) << s.error().message;
    (*s)->setTileCheck(tileCheckFor(meta(), o.baseUrl));
    return *s;
  }
  // One request for `path`, waited for.
  static FetchResult fetch(HttpTileSource& source, const std::string& path) {
    Results results;
    source.start(1, path, results.callback());
    EXPECT_TRUE(results.waitFor(1, std::chrono::seconds(60)));
    return results.take().at(0);
  }
  // The tile that a hostile answer was given for: an imagery tile, so decoding is the real test.
  static std::string imageryTile() {
    for (const auto& t : tiles())
      if (t.rfind("imagery/", 0) == 0) return t;
    return tiles().at(0);
  }
  static std::string elevationTile(size_t k) {
    size_t seen = 0;
    for (const auto& t : tiles())
      if (t.rfind("elevation/", 0) == 0 && seen++ == k) return t;
    return tiles().at(0);
  }
  std::string cacheKey(const std::string& path) const {
    return server_->baseUrl().substr(std::string("http://").size()) + "/" + path;
  }
  std::unique_ptr<FaultHttpServer> server_;
};

std::vector<Fault> times(int n, Fault f) { return std::vector<Fault>(static_cast<size_t>(n), f); }

TEST_F(HostileServer, HtmlErrorPagesAreRetriedFailedAndNeverCachedThenTheTileIsFetchedWhole) {
  auto o = options();
  o.cacheDir = work() / "cache_html";
  const std::string tile = imageryTile();
  for (FaultAction a : {FaultAction::HtmlPage, FaultAction::HtmlAsImage}) {
    fs::remove_all(*o.cacheDir);
    auto source = open(o);
    server_->scheduleForPath(tile, times(o.maxAttempts, {a}));
    const FetchResult bad = fetch(*source, tile);
    EXPECT_EQ(bad.outcome, FetchOutcome::Failed);
    EXPECT_EQ(bad.attempts, o.maxAttempts) << "an error page may be a passing proxy fault: retried";
    EXPECT_NE(bad.message.find(tile), std::string::npos) << bad.message;
    EXPECT_NE(bad.message.find(a == FaultAction::HtmlPage ? "text/html" : "not the tile"), std::string::npos)
        << bad.message;
    EXPECT_FALSE(fs::exists(*o.cacheDir / DiskTileCache::relativeFileFor(cacheKey(tile)))) << "poisoned";
    // The server heals: the tile arrives whole, and only now is cached.
    const FetchResult good = fetch(*source, tile);
    ASSERT_EQ(good.outcome, FetchOutcome::Ok) << good.message;
    EXPECT_EQ(good.bytes, fileBytes(dir() / tile));
    EXPECT_EQ(fileBytes(*o.cacheDir / DiskTileCache::relativeFileFor(cacheKey(tile))), fileBytes(dir() / tile));
  }
}

TEST_F(HostileServer, APoisonedCacheEntryIsDroppedAndFetchedAgain) {
  auto o = options();
  o.cacheDir = work() / "cache_poisoned";
  fs::remove_all(*o.cacheDir);
  const std::string tile = elevationTile(0);
  const std::string page = "<html><body>502 Bad Gateway</body></html>";
  {  // what an older vegstream stored from a proxy's error page
    auto cache = DiskTileCache::open(*o.cacheDir, 1u << 30, makeNullLogger());
    ASSERT_TRUE(cache.ok());
    ASSERT_TRUE((*cache)->put(cacheKey(tile), std::vector<uint8_t>(page.begin(), page.end())).ok());
  }
  auto source = open(o);
  const FetchResult r = fetch(*source, tile);
  ASSERT_EQ(r.outcome, FetchOutcome::Ok) << r.message;
  EXPECT_FALSE(r.fromCache);
  EXPECT_EQ(r.attempts, 1);
  EXPECT_EQ(r.bytes, fileBytes(dir() / tile));
  EXPECT_EQ(server_->requestsFor(tile), 1u);
  EXPECT_EQ(fileBytes(*o.cacheDir / DiskTileCache::relativeFileFor(cacheKey(tile))), fileBytes(dir() / tile));
  const FetchResult again = fetch(*source, tile);  // now a good copy: a hit
  EXPECT_TRUE(again.fromCache);
  EXPECT_EQ(server_->requestsFor(tile), 1u);
}

TEST_F(HostileServer, BodiesAreCappedAnnouncedOrNot) {
  auto o = options();  // 1 MiB cap
  auto source = open(o);
  for (FaultAction a : {FaultAction::EndlessBody, FaultAction::HugeLength}) {
    const std::string tile = elevationTile(a == FaultAction::EndlessBody ? 1 : 2);
    server_->scheduleForPath(tile, times(o.maxAttempts, {a}));
    const uint64_t sentBefore = server_->bytesSent();
    const auto t0 = Clock::now();
    const FetchResult r = fetch(*source, tile);
    EXPECT_EQ(r.outcome, FetchOutcome::Failed);
    EXPECT_EQ(r.attempts, 1) << "our own cap: not worth a retry";
    EXPECT_NE(r.message.find("exceeds 1048576 bytes"), std::string::npos) << r.message;
    EXPECT_LT(secondsSince(t0), 5.0);
    // The endless body was read up to the cap and no further (plus what the sockets buffer);
    // the 10 GB announcement was refused at the headers.
    const uint64_t sent = server_->bytesSent() - sentBefore;
    if (a == FaultAction::EndlessBody) {
      EXPECT_GE(sent, o.maxBodyBytes);
    }
    EXPECT_LT(sent, o.maxBodyBytes + (16u << 20)) << "read far past the cap";
  }
  // dataset.json without end: one error naming it, exit 2 for the command line.
  server_->scheduleForPath("dataset.json", {{FaultAction::EndlessBody}});
  auto text = source->readText("dataset.json");
  ASSERT_FALSE(text.ok());
  EXPECT_EQ(text.error().kind, ErrorKind::InvalidInput);
  EXPECT_NE(text.error().message.find("dataset.json"), std::string::npos) << text.error().message;
}

TEST_F(HostileServer, SlowlorisAndStallsEndByTheRequestDeadline) {
  auto o = options();
  o.maxAttempts = 100;         // only the deadline ends it
  o.requestDeadlineMs = 2500;  // and it does, whatever the attempts
  auto source = open(o);
  for (FaultAction a : {FaultAction::Slowloris, FaultAction::Stall}) {
    const std::string tile = elevationTile(a == FaultAction::Slowloris ? 3 : 4);
    server_->scheduleForPath(tile, times(100, {a}));
    const auto t0 = Clock::now();
    const FetchResult r = fetch(*source, tile);
    const double s = secondsSince(t0);
    EXPECT_EQ(r.outcome, FetchOutcome::Failed);
    EXPECT_NE(r.message.find("deadline"), std::string::npos) << r.message;
    EXPECT_GE(r.attempts, 2) << "a stalled attempt is aborted after 1 s and retried: " << r.message;
    EXPECT_GT(s, 1.0);
    EXPECT_LT(s, 2 * 2.5) << "within twice the request's deadline";
  }
}

TEST_F(HostileServer, RedirectsOnlyToHttpOnTheSameHostUnlessAllowed) {
  const std::string tile = elevationTile(5), other = elevationTile(6);
  const std::string port = std::to_string(server_->port());
  struct Case {
    std::string location;
    bool followed, followedWhenAllowed;
    std::string why;
  };
  const std::vector<Case> cases = {
      {"file:///etc/passwd", false, false, "only http:// and https://"},
      {"ftp://127.0.0.1:" + port + "/" + other, false, false, "only http:// and https://"},
      {"http://localhost:" + port + "/" + other, false, true, "another host"},
      {"/" + other, true, true, ""},  // relative: the same host
      {"http://127.0.0.1:" + port + "/" + other, true, true, ""},
  };
  for (bool allow : {false, true}) {
    auto o = options();
    o.allowRedirects = allow;
    auto source = open(o);
    for (const Case& c : cases) {
      server_->scheduleForPath(tile, {{FaultAction::Redirect, 0, c.location}});
      const uint64_t before = server_->requestsFor(other);
      const FetchResult r = fetch(*source, tile);
      const bool followed = allow ? c.followedWhenAllowed : c.followed;
      if (followed) {
        ASSERT_EQ(r.outcome, FetchOutcome::Ok) << c.location << ": " << r.message;
        EXPECT_EQ(r.bytes, fileBytes(dir() / other));
        EXPECT_EQ(server_->requestsFor(other), before + 1);
      } else {
        EXPECT_EQ(r.outcome, FetchOutcome::Failed) << c.location;
        EXPECT_EQ(r.attempts, 1);
        EXPECT_NE(r.message.find(c.why), std::string::npos) << r.message;
        EXPECT_EQ(server_->requestsFor(other), before) << "the target was never asked";
      }
    }
  }
  // A redirect loop ends after 5 hops.
  auto source = open(options());
  server_->scheduleForPath(tile, times(6, {FaultAction::Redirect, 0, "/" + tile}));
  const FetchResult loop = fetch(*source, tile);
  EXPECT_EQ(loop.outcome, FetchOutcome::Failed);
  EXPECT_NE(loop.message.find("more than 5 redirects"), std::string::npos) << loop.message;
}

}  // namespace
}  // namespace vegstream::streaming
