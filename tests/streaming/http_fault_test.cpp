// The HTTP source against a server of our own that answers with scheduled faults: retries,
// back-off, time-outs, the in-flight limit, cancellation, the disk cache and shutdown.

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <thread>

#include "core/clock.h"
#include "core/task_runner.h"
#include "datasets/http_retry_policy.h"
#include "streaming/disk_tile_cache.h"
#include "streaming/http_tile_source.h"
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
using datasets::AttemptVerdict;
using datasets::backoffDelayMs;
using datasets::judgeAttempt;
using Clock = std::chrono::steady_clock;

class FaultServer : public testing::HttpDataset {
 protected:
  void SetUp() override {
    HttpDataset::SetUp();
    if (HasFatalFailure()) return;
    server_ = std::make_unique<FaultHttpServer>(dir());
  }
  HttpSourceOptions options(int maxInFlight = 4) const {
    HttpSourceOptions o;
    o.baseUrl = server_->baseUrl();
    o.maxInFlight = maxInFlight;
    o.backoffBaseMs = 10;  // quick tests; the schedule, not the clock, decides the outcome
    o.backoffMaxMs = 40;
    o.connectTimeoutMs = 2000;
    o.totalTimeoutMs = 5000;
    return o;
  }
  std::shared_ptr<HttpTileSource> open(const HttpSourceOptions& o) const {
    auto s = HttpTileSource::create(o);
    EXPECT_TRUE(s.ok()) << s.error().message;
    return *s;
  }
  // Waits for `done` (a condition on the server's counters) for up to `limit`, woken by the
  // server whenever its counters change.
  template <typename F>
  bool eventually(F done, std::chrono::milliseconds limit = std::chrono::seconds(2)) const {
    return server_->waitUntil(done, limit);
  }
  std::unique_ptr<FaultHttpServer> server_;
};

TEST_F(FaultServer, MixedFaultsEndOkOrFailedAndCountsAddUp) {
  // Per tile, by index: the faults its path meets in order, then it is served.
  const std::vector<std::vector<Fault>> kinds = {
      {},
      {{FaultAction::Status500}},
      {{FaultAction::Status503}, {FaultAction::Status503}},
      {{FaultAction::Truncate}},
      {{FaultAction::Reset}},
      {{FaultAction::Status500, 30}, {FaultAction::Serve, 20}},
      {{FaultAction::Status500}, {FaultAction::Status503}, {FaultAction::Truncate}, {FaultAction::Status500}},
  };
  const auto o = options(4);
  auto source = open(o);
  Results results;
  const size_t n = tiles().size();
  for (size_t i = 0; i < n; ++i) server_->scheduleForPath(tiles()[i], kinds[i % kinds.size()]);
  for (size_t i = 0; i < n; ++i) source->start(i + 1, tiles()[i], results.callback());
  ASSERT_TRUE(results.waitFor(n));

  uint64_t ok = 0, failed = 0, retries = 0;
  for (const auto& r : results.take()) {
    const size_t i = r.id - 1;
    const auto& faults = kinds[i % kinds.size()];
    // Failed answers before the first served one; the request after them is served.
    const size_t failing = static_cast<size_t>(
        std::find_if(faults.begin(), faults.end(), [](const Fault& f) { return f.action == FaultAction::Serve; }) -
        faults.begin());
    const bool allFail = failing >= static_cast<size_t>(o.maxAttempts);
    retries += static_cast<uint64_t>(r.attempts - 1);
    if (allFail) {
      ++failed;
      EXPECT_EQ(r.outcome, FetchOutcome::Failed) << tiles()[i];
      EXPECT_EQ(r.attempts, o.maxAttempts);
      EXPECT_EQ(server_->requestsFor(tiles()[i]), static_cast<uint64_t>(o.maxAttempts));
      EXPECT_NE(r.message.find(tiles()[i]), std::string::npos) << r.message;
      continue;
    }
    ++ok;
    ASSERT_EQ(r.outcome, FetchOutcome::Ok) << tiles()[i] << ": " << r.message;
    EXPECT_EQ(r.bytes, fileBytes(dir() / tiles()[i])) << tiles()[i];
    EXPECT_EQ(server_->requestsFor(tiles()[i]), failing + 1) << tiles()[i];
    if (failing == 1 && faults[0].action == FaultAction::Reset)
      EXPECT_LE(r.attempts, 2) << "libcurl may resend on a fresh connection by itself after a reset";
    else
      EXPECT_EQ(r.attempts, static_cast<int>(failing) + 1) << tiles()[i];
  }
  EXPECT_TRUE(results.eachOnce(1, n));
  const SourceCounters c = source->counters();
  EXPECT_EQ(c.requestsStarted, n);
  EXPECT_EQ(c.requestsStarted, c.requestsCompleted + c.requestsMissing + c.requestsFailed + c.requestsCancelled);
  EXPECT_EQ(c.requestsCompleted, ok);
  EXPECT_EQ(c.requestsFailed, failed);
  EXPECT_GT(failed, 0u);
  EXPECT_EQ(c.retries, retries);
  EXPECT_GE(c.retries, n / 2);
  EXPECT_LE(server_->maxConcurrent(), o.maxInFlight);
  EXPECT_EQ(testing::inFlightAfterCallbacks(*source), 0u);
}

TEST_F(FaultServer, NeverMoreThanMaxInFlightAtTheServer) {
  server_->setDefault({FaultAction::Serve, 40});
  auto o = options(3);
  auto source = open(o);
  Results results;
  const size_t n = 24;
  for (size_t i = 0; i < n; ++i) source->start(i + 1, tiles()[i % tiles().size()], results.callback());
  EXPECT_LE(source->inFlight(), n);
  ASSERT_TRUE(results.waitFor(n));
  EXPECT_EQ(server_->maxConcurrent(), 3) << "the limit is reached and never passed";
  EXPECT_LE(server_->connectionsAccepted(), 4u) << "connections are kept and reused";
  EXPECT_EQ(source->counters().requestsCompleted, n);
}

TEST_F(FaultServer, AttemptSlowerThanTotalTimeoutIsRetried) {
  const std::string tile = tiles().at(0);
  server_->scheduleForPath(tile, {{FaultAction::Serve, 1500}});
  auto o = options();
  o.totalTimeoutMs = 300;
  auto source = open(o);
  Results results;
  const auto t0 = Clock::now();
  source->start(1, tile, results.callback());
  ASSERT_TRUE(results.waitFor(1));
  const auto r = results.take().at(0);
  EXPECT_EQ(r.outcome, FetchOutcome::Ok) << r.message;
  EXPECT_EQ(r.attempts, 2);
  EXPECT_LT(Clock::now() - t0, std::chrono::milliseconds(1200)) << "the slow answer was not waited for";
  EXPECT_EQ(server_->requestsFor(tile), 2u);
  EXPECT_TRUE(eventually([&] { return server_->abandoned() == 1; })) << "the timed-out attempt was closed";
}

TEST_F(FaultServer, CancelIsPromptAndStopsTheTransfer) {
  const std::string slow = tiles().at(0), queued = tiles().at(1);
  server_->scheduleForPath(slow, {{FaultAction::Serve, 5000}});
  auto source = open(options(1));
  Results results;
  source->start(1, slow, results.callback());
  source->start(2, queued, results.callback());  // waits behind the slow one (maxInFlight 1)
  ASSERT_TRUE(eventually([&] { return server_->requestsFor(slow) == 1; }));

  source->cancel(2);
  ASSERT_TRUE(results.waitFor(1, std::chrono::seconds(1)));
  EXPECT_EQ(results.take().at(0).id, 2u);
  EXPECT_EQ(results.take().at(0).outcome, FetchOutcome::Cancelled);

  const auto t0 = Clock::now();
  source->cancel(1);
  ASSERT_TRUE(results.waitFor(2, std::chrono::seconds(1)));
  EXPECT_LT(Clock::now() - t0, std::chrono::milliseconds(200));
  EXPECT_EQ(results.find(1)->outcome, FetchOutcome::Cancelled);
  EXPECT_TRUE(eventually([&] { return server_->abandoned() == 1; }, std::chrono::seconds(1)))
      << "the server saw the connection close before its answer";
  EXPECT_EQ(server_->requestsFor(queued), 0u);
  source->cancel(1);  // already called back: nothing happens
  const SourceCounters c = source->counters();
  EXPECT_EQ(c.requestsStarted, 2u);
  EXPECT_EQ(c.requestsCancelled, 2u);
  EXPECT_EQ(testing::inFlightAfterCallbacks(*source), 0u);
  EXPECT_TRUE(results.eachOnce(1, 2));
}

TEST_F(FaultServer, NotFoundAndReadTextFollowThePolicy) {
  auto source = open(options());
  server_->scheduleForPath("dataset.json", {{FaultAction::Status503}, {FaultAction::Truncate}});
  auto text = source->readText("dataset.json");
  ASSERT_TRUE(text.ok()) << text.error().message;
  EXPECT_EQ(std::vector<uint8_t>(text->begin(), text->end()), fileBytes(dir() / "dataset.json"));
  EXPECT_EQ(server_->requestsFor("dataset.json"), 3u);

  server_->scheduleForPath(tiles().at(0), {{FaultAction::NotFound}});
  Results results;
  source->start(1, tiles().at(0), results.callback());
  ASSERT_TRUE(results.waitFor(1));
  EXPECT_EQ(results.take().at(0).outcome, FetchOutcome::Missing);
  EXPECT_EQ(results.take().at(0).attempts, 1);
  EXPECT_EQ(server_->requestsFor(tiles().at(0)), 1u);

  server_->scheduleForPath(
      "no.json",
      {{FaultAction::Status500}, {FaultAction::Status500}, {FaultAction::Status500}, {FaultAction::Status500}});
  auto failed = source->readText("no.json");
  ASSERT_FALSE(failed.ok());
  EXPECT_EQ(failed.error().kind, ErrorKind::InvalidInput);  // the URL named does not deliver: exit 2
  EXPECT_NE(failed.error().message.find("no.json"), std::string::npos);
  EXPECT_EQ(server_->requestsFor("no.json"), 4u);
  auto missing = source->readText("no.json");
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.error().kind, ErrorKind::NotFound);
}

TEST_F(FaultServer, DiskCacheHitNeverTouchesTheNetwork) {
  auto o = options();
  o.cacheDir = work() / "cache_hit";
  const std::string tile = tiles().at(2);
  {
    auto source = open(o);
    Results results;
    source->start(1, tile, results.callback());
    source->start(2, tiles().at(3), results.callback());
    ASSERT_TRUE(results.waitFor(2));
    EXPECT_FALSE(results.find(1)->fromCache);
    source->start(3, tile, results.callback());
    ASSERT_TRUE(results.waitFor(3));
    EXPECT_TRUE(results.find(3)->fromCache);
    EXPECT_EQ(results.find(3)->bytes, fileBytes(dir() / tile));
    EXPECT_EQ(source->counters().cacheHits, 1u);
  }
  // A new source over the same cache directory (a restart) still has it.
  auto source = open(o);
  Results results;
  source->start(1, tile, results.callback());
  ASSERT_TRUE(results.waitFor(1));
  const auto r = results.take().at(0);
  EXPECT_EQ(r.outcome, FetchOutcome::Ok);
  EXPECT_TRUE(r.fromCache);
  EXPECT_EQ(r.attempts, 0);
  EXPECT_EQ(r.bytes, fileBytes(dir() / tile));
  EXPECT_EQ(server_->requestsFor(tile), 1u);
  EXPECT_EQ(source->counters().cacheHits, 1u);
  EXPECT_EQ(source->counters().requestsCompleted, 1u);
}

TEST_F(FaultServer, DiskCacheStaysWithinItsBudget) {
  constexpr size_t kTiles = 10;
  ASSERT_GE(tiles().size(), kTiles);
  uint64_t total = 0;
  for (size_t i = 0; i < kTiles; ++i) total += fs::file_size(dir() / tiles()[i]);
  auto o = options();
  o.cacheDir = work() / "cache_budget";
  o.cacheBudgetBytes = total / 3;
  auto source = open(o);
  Results results;
  for (size_t i = 0; i < kTiles; ++i) {  // one at a time: the use order is the fetch order
    source->start(i + 1, tiles()[i], results.callback());
    ASSERT_TRUE(results.waitFor(i + 1));
  }
  uint64_t onDisk = 0;
  size_t files = 0;
  for (const auto& e : fs::recursive_directory_iterator(*o.cacheDir))
    if (e.is_regular_file()) onDisk += e.file_size(), ++files;
  EXPECT_LE(onDisk, o.cacheBudgetBytes);
  EXPECT_GT(files, 0u);
  EXPECT_LT(files, kTiles);

  // The newest is kept, the oldest was evicted.
  source->start(100, tiles()[kTiles - 1], results.callback());
  source->start(101, tiles()[0], results.callback());
  ASSERT_TRUE(results.waitFor(kTiles + 2));
  EXPECT_TRUE(results.find(100)->fromCache);
  EXPECT_FALSE(results.find(101)->fromCache);
  EXPECT_EQ(server_->requestsFor(tiles()[kTiles - 1]), 1u);
  EXPECT_EQ(server_->requestsFor(tiles()[0]), 2u);
}

TEST_F(FaultServer, DestroyingWithRequestsInFlightCallsEachBackOnce) {
  server_->setDefault({FaultAction::Serve, 3000});
  Results results;
  const size_t n = 12;
  const auto t0 = Clock::now();
  {
    auto source = open(options(4));
    for (size_t i = 0; i < n; ++i) source->start(i + 1, tiles()[i % tiles().size()], results.callback());
    ASSERT_TRUE(eventually([&] { return server_->totalRequests() == 4; })) << server_->totalRequests();
  }
  EXPECT_LT(Clock::now() - t0, std::chrono::seconds(1));
  EXPECT_TRUE(results.eachOnce(1, n));
  for (const auto& r : results.take()) EXPECT_EQ(r.outcome, FetchOutcome::Cancelled);
  EXPECT_TRUE(eventually([&] { return server_->abandoned() == 4; }));
}

// The back-off is measured on the injected clock: with a ManualClock that does not move, a
// tile answered 503 is not asked again however long the test waits; once the clock has passed
// the delay (and the I/O task is woken), the second attempt goes out and is served.
TEST_F(FaultServer, BackOffWaitsForTheInjectedClock) {
  ManualClock clock(100.0);
  auto o = options(1);
  o.backoffBaseMs = 1000;  // the second attempt after 0.5 … 1 s of the clock's time
  o.backoffMaxMs = 1000;
  o.clock = &clock;
  auto source = open(o);
  const std::string tile = tiles()[0];
  server_->scheduleForPath(tile, {{FaultAction::Status503}});
  Results results;
  source->start(1, tile, results.callback());
  ASSERT_TRUE(eventually([&] { return server_->requestsFor(tile) == 1; }));
  // Real time passes, the clock's does not: no retry (a bounded wait on the callback's condition).
  EXPECT_FALSE(results.waitFor(1, std::chrono::milliseconds(300)));
  EXPECT_EQ(server_->requestsFor(tile), 1u);
  clock.advance(0.2);  // not yet: the delay is at least 0.5 s
  source->wake();
  EXPECT_FALSE(results.waitFor(1, std::chrono::milliseconds(100)));
  clock.advance(1.0);
  source->wake();
  ASSERT_TRUE(results.waitFor(1));
  const auto r = results.find(1);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->outcome, FetchOutcome::Ok) << r->message;
  EXPECT_EQ(r->attempts, 2);
  EXPECT_EQ(server_->requestsFor(tile), 2u);
}

// The I/O loop is a task of the injected runner: a runner that never runs it (a ManualTaskRunner
// the test does not step) leaves requests unanswered, and the destructor still ends them all
// Cancelled by running the loop's shutdown itself.
TEST_F(FaultServer, TheIoLoopRunsOnTheInjectedRunner) {
  ManualTaskRunner tasks;
  Results results;
  {
    auto o = options(2);
    o.tasks = &tasks;
    auto source = open(o);
    EXPECT_EQ(tasks.pending(), 1u) << "the long-running I/O task";
    for (RequestId id = 1; id <= 3; ++id) source->start(id, tiles()[id], results.callback());
    EXPECT_FALSE(results.waitFor(1, std::chrono::milliseconds(100)));
    EXPECT_EQ(server_->totalRequests(), 0u);
  }
  ASSERT_TRUE(results.waitFor(3, std::chrono::milliseconds(0)));
  for (const auto& r : results.take()) EXPECT_EQ(r.outcome, FetchOutcome::Cancelled) << r.id;
  EXPECT_TRUE(results.eachOnce(1, 3));
  EXPECT_EQ(tasks.runAll(), 1u);  // the loop's task, run late, returns at once
}

TEST(HttpRetryPolicy, JudgesAttempts) {
  auto judge = [](CURLcode code, long status, int64_t length = -1, uint64_t body = 0) {
    return judgeAttempt({code, status, length, body});
  };
  EXPECT_EQ(judge(CURLE_OK, 200, 10, 10), AttemptVerdict::Ok);
  EXPECT_EQ(judge(CURLE_OK, 200, 10, 5), AttemptVerdict::Retry);
  EXPECT_EQ(judge(CURLE_OK, 404), AttemptVerdict::Missing);
  EXPECT_EQ(judge(CURLE_OK, 410), AttemptVerdict::Missing);
  EXPECT_EQ(judge(CURLE_OK, 403), AttemptVerdict::Fail);
  EXPECT_EQ(judge(CURLE_OK, 400), AttemptVerdict::Fail);
  EXPECT_EQ(judge(CURLE_OK, 429), AttemptVerdict::Retry);
  EXPECT_EQ(judge(CURLE_OK, 500), AttemptVerdict::Retry);
  EXPECT_EQ(judge(CURLE_OK, 503), AttemptVerdict::Retry);
  EXPECT_EQ(judge(CURLE_OPERATION_TIMEDOUT, 0), AttemptVerdict::Retry);
  EXPECT_EQ(judge(CURLE_COULDNT_CONNECT, 0), AttemptVerdict::Retry);
  EXPECT_EQ(judge(CURLE_RECV_ERROR, 0), AttemptVerdict::Retry);
  EXPECT_EQ(judge(CURLE_PARTIAL_FILE, 200), AttemptVerdict::Retry);
  EXPECT_EQ(judge(CURLE_URL_MALFORMAT, 0), AttemptVerdict::Fail);
}

TEST(HttpRetryPolicy, BackoffGrowsIsCappedAndJittered) {
  for (uint64_t key = 0; key < 200; ++key) {
    for (int attempt = 2; attempt <= 8; ++attempt) {
      const long raw = std::min(3000L, 100L << (attempt - 2));
      const long d = backoffDelayMs(attempt, key, 100, 3000);
      EXPECT_GE(d, raw / 2);
      EXPECT_LE(d, raw);
      EXPECT_EQ(d, backoffDelayMs(attempt, key, 100, 3000)) << "deterministic";
    }
  }
  EXPECT_NE(backoffDelayMs(3, 1, 100, 3000), backoffDelayMs(3, 2, 100, 3000)) << "jittered per request";
}

TEST(DiskTileCacheNames, KeysStayInsideTheDirectory) {
  const auto rel = DiskTileCache::relativeFileFor("127.0.0.1:8080/a/../b c/x.png");
  EXPECT_EQ(rel.generic_string(), "127.0.0.1_3A8080/a/_2E_2E/b_20c/x.png");
  EXPECT_NE(DiskTileCache::relativeFileFor("h/a_b"), DiskTileCache::relativeFileFor("h/a/b"));
}

}  // namespace
}  // namespace vegstream::streaming
