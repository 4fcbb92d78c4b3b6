// The pieces of issue 42's HTTP limits that need no hostile server (the redirect rule, textual
// Content-Types, the verdicts on capped bodies and error pages, the tile check), and the blocking
// ground loads against one: stalled and failing tiles end as no data within the deadline, and
// only a ground of which every tile failed is an error.

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

#include "datasets/http_fetch.h"
#include "datasets/http_limits.h"
#include "datasets/http_retry_policy.h"
#include "streaming/dataset_snapshot.h"
#include "streaming/http_tile_source.h"
#include "streaming/tile_check.h"
#include "tests/streaming/http_test_dataset.h"
#include "tests/support/fault_http_server.h"

namespace vegstream::streaming {
namespace {
using datasets::AttemptEnd;
using datasets::AttemptVerdict;
using testing::Fault;
using testing::FaultAction;
using testing::FaultHttpServer;
using testing::fileBytes;
using Clock = std::chrono::steady_clock;

TEST(HttpLimits, RedirectTargetsAreHttpOnTheSameHostUnlessAnyHost) {
  const std::string from = "http://tiles.example.org:8080/zion/elevation/1/2/3.png";
  EXPECT_TRUE(datasets::redirectTarget(from, "http://tiles.example.org:8080/other/1.png", false).ok());
  EXPECT_TRUE(datasets::redirectTarget(from, "http://TILES.example.org:8080/x", false).ok()) << "hosts are caseless";
  for (const char* to : {"http://cdn.example.org:8080/x", "http://tiles.example.org:8081/x",
                         "http://tiles.example.org/x"}) {
    auto r = datasets::redirectTarget(from, to, false);
    ASSERT_FALSE(r.ok()) << to;
    EXPECT_NE(r.error().message.find("another host"), std::string::npos) << r.error().message;
    EXPECT_NE(r.error().message.find(from), std::string::npos) << r.error().message;
    EXPECT_TRUE(datasets::redirectTarget(from, to, true).ok()) << to;
  }
  for (const char* to : {"file:///etc/passwd", "ftp://tiles.example.org:8080/x", "gopher://x/", "dict://x/"}) {
    for (bool any : {false, true}) {
      auto r = datasets::redirectTarget(from, to, any);
      ASSERT_FALSE(r.ok()) << to;
      EXPECT_NE(r.error().message.find("only http:// and https://"), std::string::npos) << r.error().message;
    }
  }
  EXPECT_FALSE(datasets::redirectTarget(from, "", true).ok());
}

TEST(HttpLimits, TextualContentTypesAndTheirVerdicts) {
  for (const char* t : {"text/html", "text/html; charset=utf-8", "TEXT/PLAIN", "application/json",
                        "application/problem+json", "application/xml", "application/xhtml+xml"})
    EXPECT_TRUE(datasets::textualContentType(t)) << t;
  for (const char* t : {"", "image/png", "image/jpeg", "image/webp", "application/octet-stream",
                        "application/vnd.pmtiles"})
    EXPECT_FALSE(datasets::textualContentType(t)) << t;
  AttemptEnd page;
  page.httpStatus = 200;
  page.contentType = "text/html";
  page.binaryExpected = true;
  EXPECT_EQ(datasets::judgeAttempt(page), AttemptVerdict::Retry);
  EXPECT_NE(datasets::describeAttempt(page, nullptr).find("text/html"), std::string::npos);
  page.binaryExpected = false;  // dataset.json may be text
  EXPECT_EQ(datasets::judgeAttempt(page), AttemptVerdict::Ok);
  AttemptEnd endless;
  endless.code = CURLE_WRITE_ERROR;
  endless.httpStatus = 200;
  endless.bodyExceeded = true;
  endless.bodyCap = 1000;
  EXPECT_EQ(datasets::judgeAttempt(endless), AttemptVerdict::Fail);
  EXPECT_EQ(datasets::describeAttempt(endless, nullptr), "the body exceeds 1000 bytes");
  AttemptEnd huge;
  huge.code = CURLE_FILESIZE_EXCEEDED;
  EXPECT_EQ(datasets::judgeAttempt(huge), AttemptVerdict::Fail);
  EXPECT_EQ(datasets::attemptTimeoutWithin(20000, 1500.2), 1501);
  EXPECT_EQ(datasets::attemptTimeoutWithin(20000, -5.0), 1) << "never 0: libcurl reads it as no time-out";
  EXPECT_EQ(datasets::attemptTimeoutWithin(20000, 1e9), 20000);
}

class GroundLoad : public testing::HttpDataset {
 protected:
  void SetUp() override {
    HttpDataset::SetUp();
    if (HasFatalFailure()) return;
    server_ = std::make_unique<FaultHttpServer>(dir());
  }
  std::shared_ptr<HttpTileSource> open(long requestDeadlineMs) const {
    HttpSourceOptions o;
    o.baseUrl = server_->baseUrl();
    o.backoffBaseMs = 10;
    o.backoffMaxMs = 40;
    o.lowSpeedTimeS = 1;
    o.requestDeadlineMs = requestDeadlineMs;
    auto s = HttpTileSource::create(o);
    EXPECT_TRUE(s.ok()) << s.error().message;
    return *s;
  }
  std::vector<std::string> elevationTiles() const {
    std::vector<std::string> out;
    for (const auto& t : tiles())
      if (t.rfind("elevation/", 0) == 0) out.push_back(t);
    return out;
  }
  std::unique_ptr<FaultHttpServer> server_;
};

TEST_F(GroundLoad, TilesThatCheckDecodeAndOthersDoNot) {
  const TileCheck check = tileCheckFor(meta(), "URL");
  for (const auto& t : tiles()) EXPECT_TRUE(check(t, fileBytes(dir() / t)).ok()) << t;
  const std::string page = "<html>502</html>";
  const std::vector<uint8_t> html(page.begin(), page.end());
  const std::string tile = elevationTiles().at(0);
  const auto bad = check(tile, html);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("URL/" + tile), std::string::npos) << bad.error().message;
  EXPECT_TRUE(check("dataset.json", html).ok()) << "only tiles are checked";
}

// 10 % of the ground's tiles stall, one more is an HTML page: the ground still loads, those
// tiles are no data, and it takes about one request deadline, not one per stalled tile.
TEST_F(GroundLoad, StalledAndBadTilesBecomeNoDataWithinTheDeadline) {
  auto source = open(2000);
  SnapshotLimits limits;
  limits.maxHeightPixels = 1u << 30;
  const auto all = loadGroundHeights(*source, meta(), limits);  // healthy: the reference
  ASSERT_TRUE(all.ok()) << all.error().message;
  const auto tileList = elevationTiles();
  const size_t stalled = std::max<size_t>(1, tileList.size() / 10);
  size_t z = 0;
  for (const auto& t : tileList) {
    if (t.find("/" + std::to_string(all->zoom) + "/") == std::string::npos) continue;
    server_->scheduleForPath(t, std::vector<Fault>(50, z < stalled ? Fault{FaultAction::Stall} : Fault{FaultAction::HtmlPage}));
    if (++z > stalled) break;
  }
  ASSERT_GE(z, 2u) << "the ground's zoom has tiles";
  const auto t0 = Clock::now();
  const auto partial = loadGroundHeights(*source, meta(), limits);
  const double s = std::chrono::duration<double>(Clock::now() - t0).count();
  ASSERT_TRUE(partial.ok()) << partial.error().message;
  EXPECT_LT(s, 2 * 2.0) << "the stalled tiles wait out one deadline together";
  size_t finiteAll = 0, finitePartial = 0;
  for (float h : all->heights) finiteAll += std::isfinite(h);
  for (float h : partial->heights) finitePartial += std::isfinite(h);
  EXPECT_LT(finitePartial, finiteAll) << "the failed tiles are no data";
  EXPECT_GT(finitePartial, 0u);

  // The batch's own deadline ends it too, whatever the requests' deadlines.
  auto patient = open(60'000);
  limits.deadlineMs = 1500;
  for (const auto& t : tileList) server_->scheduleForPath(t, std::vector<Fault>(50, Fault{FaultAction::Stall}));
  const auto t1 = Clock::now();
  const auto none = loadGroundHeights(*patient, meta(), limits);
  EXPECT_LT(std::chrono::duration<double>(Clock::now() - t1).count(), 2 * 1.5);
  ASSERT_FALSE(none.ok()) << "every tile failed: no ground at all";
  EXPECT_EQ(none.error().kind, ErrorKind::InvalidInput);
  EXPECT_NE(none.error().message.find("deadline"), std::string::npos) << none.error().message;
  EXPECT_NE(none.error().message.find(server_->baseUrl()), std::string::npos) << none.error().message;
}

// The importer's URL fetches (datasets/http_fetch.h) meet the same hostile answers: capped,
// ended by their deadline, and not led to another host or protocol.
TEST_F(GroundLoad, TheImportersFetcherKeepsTheSameLimits) {
  datasets::HttpFetchOptions o;
  o.maxBodyBytes = 1u << 20;
  o.lowSpeedTimeS = 1;
  o.requestDeadlineMs = 2500;
  o.maxAttempts = 100;
  o.backoffBaseMs = 10;
  o.backoffMaxMs = 40;
  datasets::HttpFetcher fetcher(o);
  const auto list = elevationTiles();
  const std::string base = server_->baseUrl() + "/";
  auto expectFailure = [&](const std::string& tile, std::vector<Fault> faults, const std::string& why, double maxS) {
    server_->scheduleForPath(tile, std::move(faults));
    const auto t0 = Clock::now();
    auto r = fetcher.get(base + tile);
    const double s = std::chrono::duration<double>(Clock::now() - t0).count();
    ASSERT_FALSE(r.ok()) << tile;
    EXPECT_EQ(r.error().kind, ErrorKind::InvalidInput);
    EXPECT_NE(r.error().message.find(why), std::string::npos) << r.error().message;
    EXPECT_LT(s, maxS) << r.error().message;
  };
  expectFailure(list.at(0), {{FaultAction::EndlessBody}}, "exceeds 1048576 bytes", 5.0);
  expectFailure(list.at(1), {{FaultAction::HugeLength}}, "exceeds 1048576 bytes", 5.0);
  expectFailure(list.at(2), std::vector<Fault>(100, Fault{FaultAction::Stall}), "deadline", 2 * 2.5);
  expectFailure(list.at(3), {{FaultAction::Redirect, 0, "ftp://127.0.0.1/x"}}, "only http:// and https://", 5.0);
  expectFailure(list.at(4), {{FaultAction::Redirect, 0, "http://localhost:" + std::to_string(server_->port()) + "/" + list.at(5)}},
                "another host", 5.0);
  EXPECT_EQ(server_->requestsFor(list.at(5)), 0u);
  // The same host is followed; with allowRedirects another host is too.
  server_->scheduleForPath(list.at(6), {{FaultAction::Redirect, 0, "/" + list.at(5)}});
  auto same = fetcher.get(base + list.at(6));
  ASSERT_TRUE(same.ok() && *same) << (same.ok() ? "missing" : same.error().message);
  EXPECT_EQ(**same, fileBytes(dir() / list.at(5)));
  o.allowRedirects = true;
  datasets::HttpFetcher open(o);
  server_->scheduleForPath(list.at(7), {{FaultAction::Redirect, 0, "http://localhost:" + std::to_string(server_->port()) + "/" + list.at(5)}});
  auto other = open.get(base + list.at(7));
  ASSERT_TRUE(other.ok() && *other) << (other.ok() ? "missing" : other.error().message);
  EXPECT_EQ(**other, fileBytes(dir() / list.at(5)));
}

}  // namespace
}  // namespace vegstream::streaming
