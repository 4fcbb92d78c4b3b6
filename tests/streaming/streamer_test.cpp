// TileStreamer over a real dataset directory (LocalTileSource) and, for failures and timing,
// over a scripted source: residency and decoded values, the CPU budget, cancellation, request
// order, missing and failing tiles, the counters, settle and shutdown.
//
// Nothing here sleeps: reads and decodes run on a ManualTaskRunner the test steps (runAll), the
// scripted source is waited on with a condition (waitDelivered), and settle() waits on the
// streamer's own condition over a real ThreadPool.

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <random>
#include <set>
#include <thread>

#include "core/task_runner.h"

#include "datasets/tile_codec.h"
#include "scripted_tile_source.h"
#include "streaming/local_tile_source.h"
#include "streaming_fixture.h"

namespace vegstream::streaming::test {
namespace {

constexpr uint64_t kTileBytes = 256 * 256 * 4;

std::vector<uint8_t> fileBytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Repeats update() (time advancing 10 ms a call) until pred() holds, running `between` (what
// the workers would do meanwhile) after each; false after 1000 updates.
template <typename Pred, typename Between>
bool updateUntil(TileStreamer& s, const std::vector<TileWant>& wants, double& t, Pred pred, Between between) {
  for (int i = 0; i < 1000; ++i) {
    s.update(wants, t);
    t += 0.01;
    if (pred()) return true;
    between();
  }
  return false;
}

// Running sums of the per-frame counters.
struct Totals {
  uint64_t issued = 0, completed = 0, cancelled = 0, failed = 0, missing = 0;
  void add(const StreamingFrameStats& f) {
    issued += f.requestsIssued;
    completed += f.requestsCompleted;
    cancelled += f.requestsCancelled;
    failed += f.requestsFailed;
    missing += f.requestsMissing;
  }
  // Every request issued is resident, cancelled, failed, missing, or still under way.
  void expectBalanced(const StreamingFrameStats& f) const {
    EXPECT_EQ(issued, completed + cancelled + failed + missing + f.requestsInFlight + f.decodesQueued)
        << "issued " << issued << " completed " << completed << " cancelled " << cancelled << " failed " << failed
        << " missing " << missing << " in flight " << f.requestsInFlight << " decoding " << f.decodesQueued;
  }
};

StreamingOptions smallOptions(TaskRunner* tasks = nullptr) {
  StreamingOptions o;
  o.decodeThreads = 2;
  o.maxRequestsInFlight = 8;
  o.tasks = tasks;
  return o;
}

using StreamerLocal = SyntheticDataset;

TEST_F(StreamerLocal, SettleMakesEveryWantedTileResidentWithTheHeightsOfReadHeightTile) {
  auto source = std::make_shared<LocalTileSource>(dir());
  TileStreamer s(source, meta(), smallOptions(), makeNullLogger());
  auto keys = tilesAt(dir(), meta(), TileLayer::Height, meta().maxZoom);
  const auto colour = tilesAt(dir(), meta(), TileLayer::Imagery, meta().maxZoom);
  ASSERT_GE(keys.size(), 9u);
  ASSERT_EQ(colour.size(), keys.size());
  keys.insert(keys.end(), colour.begin(), colour.end());
  const auto wants = wantsOf(keys);
  const double waited = s.settle(wants, 0.0);
  EXPECT_LT(waited, 30.0);
  EXPECT_EQ(s.frameStats().wanted, keys.size());
  EXPECT_EQ(s.frameStats().wantedResident, keys.size());
  EXPECT_EQ(s.frameStats().bytesResidentCpu, s.frameStats().tilesResidentCpu * (kTileBytes + 256));
  for (const auto& k : keys) {
    EXPECT_EQ(s.state(k), TileState::ResidentCpu) << toString(k);
    const auto tile = s.get(k);
    ASSERT_TRUE(tile) << toString(k);
    if (k.layer == TileLayer::Height) {
      auto ref = datasets::readHeightTile(dir() / datasetRelativePath(k, meta()), k.id, meta().elevationEncoding,
                                          datasets::kTileSize);
      ASSERT_TRUE(ref) << ref.error().message;
      ASSERT_TRUE(tile->heights);
      ASSERT_EQ(tile->heights->heights.size(), ref->heights.size());
      for (size_t i = 0; i < ref->heights.size(); ++i)
        ASSERT_TRUE(tile->heights->heights[i] == ref->heights[i] ||
                    (std::isnan(tile->heights->heights[i]) && std::isnan(ref->heights[i])));
    } else {
      auto ref = datasets::readColorTile(dir() / datasetRelativePath(k, meta()), k.id, datasets::kTileSize);
      ASSERT_TRUE(ref) << ref.error().message;
      ASSERT_TRUE(tile->colors);
      EXPECT_EQ(tile->colors->rgba, ref->rgba);
    }
  }
  EXPECT_EQ(source->counters().requestsCompleted, keys.size());
}

// 40 rounds of random wants (some current, some look-ahead) under a budget of 12 tiles, each
// round updated until nothing is under way: resident bytes never exceed the budget at any
// update, and a current want that is resident stays resident.
TEST_F(StreamerLocal, CpuBudgetHoldsAndCurrentWantsAreNeverEvicted) {
  ManualTaskRunner tasks;  // reads and decodes run between updates, when the test says
  auto source = std::make_shared<LocalTileSource>(dir(), 2, &tasks);
  StreamingOptions o = smallOptions(&tasks);
  o.cpuBudgetBytes = 12 * (kTileBytes + 256);
  TileStreamer s(source, meta(), o, makeNullLogger());
  std::vector<TileKey> pool;
  for (int z = meta().minZoom; z <= meta().maxZoom; ++z)
    for (auto layer : {TileLayer::Height, TileLayer::Imagery})
      for (const auto& k : tilesAt(dir(), meta(), layer, z)) pool.push_back(k);
  ASSERT_GT(pool.size(), 30u);
  std::mt19937 rng(5);
  Totals totals;
  uint64_t evictions = 0, exceeded = 0, updates = 0;
  double t = 0.0;
  for (int round = 0; round < 40; ++round) {
    std::shuffle(pool.begin(), pool.end(), rng);
    const size_t current = std::uniform_int_distribution<size_t>(1, 14)(rng);  // sometimes over budget
    std::vector<TileWant> wants;
    for (size_t i = 0; i < current + 6; ++i) wants.push_back({pool[i], double(rng() % 100), i >= current});
    for (int frame = 0; frame < 2000; ++frame) {
      std::vector<TileKey> residentBefore;
      for (size_t i = 0; i < current; ++i)
        if (s.state(pool[i]) == TileState::ResidentCpu) residentBefore.push_back(pool[i]);
      s.update(wants, t);
      t += 1.0 / 60.0;
      ++updates;
      const auto& f = s.frameStats();
      totals.add(f);
      ASSERT_LE(f.bytesResidentCpu, o.cpuBudgetBytes) << "round " << round << " frame " << frame;
      for (const auto& k : residentBefore) ASSERT_EQ(s.state(k), TileState::ResidentCpu) << toString(k);
      evictions += f.evictionsCpu;
      exceeded += f.wantsExceedCpuBudget ? 1 : 0;
      totals.expectBalanced(f);
      if (f.requestsInFlight + f.decodesQueued == 0) break;
      // Some of the work, so that completions land between updates in varying numbers.
      for (int k = 0; k < 1 + frame % 5; ++k) tasks.runOne();
    }
  }
  EXPECT_GT(updates, 80u);
  EXPECT_GT(evictions, 20u);
  EXPECT_GT(exceeded, 0u);  // 13 and 14 current wants do not fit in 12
  EXPECT_GT(totals.completed, 100u);
  EXPECT_EQ(totals.missing + totals.failed, 0u);
}

TEST_F(StreamerLocal, AWantThatGoesAwayIsCancelledAndNeverResident) {
  ManualTaskRunner tasks;
  auto source = std::make_shared<LocalTileSource>(dir(), 1, &tasks);
  StreamingOptions o = smallOptions(&tasks);
  o.maxRequestsInFlight = 64;
  TileStreamer s(source, meta(), o, makeNullLogger());
  auto keys = tilesAt(dir(), meta(), TileLayer::Imagery, meta().maxZoom);
  ASSERT_GE(keys.size(), 6u);
  s.update(wantsOf(keys), 0.0);
  EXPECT_EQ(s.frameStats().requestsIssued, keys.size());
  Totals totals;
  totals.add(s.frameStats());
  // Read, decode, read, decode, read (each read posts its decode and then itself again): two
  // tiles decoded, one fetched and queued for decoding, the rest still queued at the source.
  for (int i = 0; i < 5; ++i) ASSERT_TRUE(tasks.runOne());
  s.update({}, 0.01);  // nothing wanted any more: all still under way are cancelled
  totals.add(s.frameStats());
  EXPECT_EQ(s.frameStats().requestsCompleted, 0u) << "cancelled before the completions were taken";
  EXPECT_EQ(s.frameStats().requestsCancelled, keys.size());
  tasks.runAll();  // the source answers the rest (cancelled); no decode is left to run
  EXPECT_EQ(source->inFlight(), 0u);
  s.update({}, 0.2);
  totals.add(s.frameStats());
  uint64_t resident = 0;
  for (const auto& k : keys) resident += s.state(k) == TileState::ResidentCpu ? 1u : 0u;
  // Nothing that was cancelled became resident, decoded or not.
  EXPECT_EQ(resident, 0u);
  EXPECT_EQ(resident, totals.completed);
  EXPECT_EQ(totals.issued, totals.completed + totals.cancelled);
  EXPECT_TRUE(s.planUploads().empty());
}

// settle() is a function of the wants and the flight time only: the same frames of wants
// (current and look-ahead, over a CPU budget that forces evictions) settled by two streamers —
// one reading and decoding one tile at a time, one with several reads and decodes racing on a
// pool — leave every tile in the same state after every frame, with the same counters, and
// nothing in flight (look-ahead included).
TEST_F(StreamerLocal, SettleGivesTheSameTilesWhateverOrderTheWorkersFinishIn) {
  ThreadPool one(1), many(4);
  StreamingOptions oa = smallOptions(&one), ob = smallOptions(&many);
  oa.decodeThreads = 1;
  ob.decodeThreads = 3;
  oa.cpuBudgetBytes = ob.cpuBudgetBytes = 14 * (kTileBytes + 256);
  TileStreamer a(std::make_shared<LocalTileSource>(dir(), 1, &one), meta(), oa, makeNullLogger());
  TileStreamer b(std::make_shared<LocalTileSource>(dir(), 3, &many), meta(), ob, makeNullLogger());
  std::vector<TileKey> pool;
  for (int z = meta().minZoom; z <= meta().maxZoom; ++z)
    for (auto layer : {TileLayer::Height, TileLayer::Imagery})
      for (const auto& k : tilesAt(dir(), meta(), layer, z)) pool.push_back(k);
  ASSERT_GT(pool.size(), 30u);
  std::mt19937 rng(7);
  uint64_t evictions = 0, lookAheadResident = 0;
  for (int frame = 0; frame < 16; ++frame) {
    std::shuffle(pool.begin(), pool.end(), rng);
    std::vector<TileWant> wants;
    for (size_t i = 0; i < 10; ++i) wants.push_back({pool[i], double(rng() % 100), i >= 6});
    const double t = frame * 0.25;
    a.settle(wants, t);
    b.settle(wants, t);
    const StreamingFrameStats& fa = a.frameStats();
    const StreamingFrameStats& fb = b.frameStats();
    EXPECT_EQ(fa.requestsInFlight + fa.decodesQueued, 0u) << "frame " << frame;
    EXPECT_EQ(fb.requestsInFlight + fb.decodesQueued, 0u) << "frame " << frame;
    EXPECT_EQ(fa.requestsIssued, fb.requestsIssued) << "frame " << frame;
    EXPECT_EQ(fa.requestsCompleted, fb.requestsCompleted) << "frame " << frame;
    EXPECT_EQ(fa.evictionsCpu, fb.evictionsCpu) << "frame " << frame;
    EXPECT_EQ(fa.bytesResidentCpu, fb.bytesResidentCpu) << "frame " << frame;
    for (const TileKey& k : pool) ASSERT_EQ(a.state(k), b.state(k)) << toString(k) << " frame " << frame;
    for (size_t i = 6; i < 10; ++i) lookAheadResident += a.state(pool[i]) == TileState::ResidentCpu ? 1u : 0u;
    evictions += fa.evictionsCpu;
    // The frame's readers touch the same tiles in both (LRU order stays the same).
    for (size_t i = 0; i < 3; ++i) {
      (void)a.findResident(pool[i]);
      (void)b.findResident(pool[i]);
    }
  }
  EXPECT_GT(evictions, 5u) << "the budget made the streamers choose what to evict";
  EXPECT_GT(lookAheadResident, 10u) << "look-ahead wants were settled too";
}

TEST_F(StreamerLocal, MissingTileFailsForGoodAndItsParentIsFound) {
  const fs::path copy = testTmp("missing");
  fs::copy(dir(), copy, fs::copy_options::recursive);
  const auto keys = tilesAt(copy, meta(), TileLayer::Height, meta().maxZoom);
  const TileKey gone = keys[keys.size() / 2];
  fs::remove(copy / datasetRelativePath(gone, meta()));
  auto source = std::make_shared<LocalTileSource>(copy);
  TileStreamer s(source, meta(), smallOptions(), makeNullLogger());
  const std::vector<TileWant> wants = {{gone, 2.0, false}, {parentOf(gone), 1.0, false}};
  s.settle(wants, 0.0);
  EXPECT_EQ(s.state(gone), TileState::Failed);
  EXPECT_FALSE(s.failure(gone)) << "a missing tile has not failed: its parent answers for it";
  EXPECT_EQ(source->counters().requestsMissing, 1u);
  const auto found = s.findResident(gone);
  ASSERT_TRUE(found.tile);
  EXPECT_EQ(found.levelsUp, 1);
  EXPECT_EQ(found.tile->key, parentOf(gone));
  // Failed is final: not asked again, even long after.
  s.update(wants, 100.0);
  EXPECT_EQ(s.frameStats().requestsIssued, 0u);
  EXPECT_EQ(source->counters().requestsStarted, 2u);
  fs::remove_all(copy);
}

TEST_F(StreamerLocal, DestructorWithRequestsInFlightIsClean) {
  ManualTaskRunner tasks;  // outlives both: what they posted runs after the streamer is gone
  auto source = std::make_shared<LocalTileSource>(dir(), 1, &tasks);
  {
    StreamingOptions o = smallOptions(&tasks);
    o.maxRequestsInFlight = 64;
    TileStreamer s(source, meta(), o, makeNullLogger());
    auto keys = tilesAt(dir(), meta(), TileLayer::Height, meta().maxZoom);
    const auto more = tilesAt(dir(), meta(), TileLayer::Imagery, meta().maxZoom);
    keys.insert(keys.end(), more.begin(), more.end());
    s.update(wantsOf(keys), 0.0);
    EXPECT_EQ(s.frameStats().requestsInFlight, keys.size());
    for (int i = 0; i < 3; ++i) tasks.runOne();  // a read, its decode task posted, another read
  }
  // The source outlives the streamer: its callbacks still arrive, safely, and every request
  // ends; decode tasks posted before the streamer went find the pipeline closed.
  EXPECT_GT(source->inFlight(), 0u);
  EXPECT_GT(tasks.runAll(), 0u);
  EXPECT_EQ(source->inFlight(), 0u);
  const auto c = source->counters();
  EXPECT_EQ(c.requestsStarted, c.requestsCompleted + c.requestsCancelled);
}

// ---- scripted source: order, failures, counters ----

using StreamerScripted = SyntheticDataset;

TEST_F(StreamerScripted, RequestsGoOutInPriorityOrderCurrentBeforeLookAhead) {
  auto source = std::make_shared<ScriptedSource>();  // holds everything
  StreamingOptions o = smallOptions();
  o.maxRequestsInFlight = 3;
  TileStreamer s(source, meta(), o, makeNullLogger());
  const auto keys = tilesAt(dir(), meta(), TileLayer::Height, meta().maxZoom);
  ASSERT_GE(keys.size(), 8u);
  // Current wants with priorities 1 … 5 (listed out of order), look-ahead ones with 100, 99.
  std::vector<TileWant> wants = {{keys[0], 3, false}, {keys[1], 5, false},  {keys[2], 1, false}, {keys[3], 4, false},
                                 {keys[4], 2, false}, {keys[5], 100, true}, {keys[6], 99, true}};
  s.update(wants, 0.0);
  auto started = source->started();
  ASSERT_EQ(started.size(), 3u);
  EXPECT_EQ(started[0].path, datasetRelativePath(keys[1], meta()));
  EXPECT_EQ(started[1].path, datasetRelativePath(keys[3], meta()));
  EXPECT_EQ(started[2].path, datasetRelativePath(keys[0], meta()));
  // Answer them Missing: the next two current wants go out, then the first look-ahead one.
  for (const auto& st : started) source->reply(st.id, ScriptedSource::outcome(FetchOutcome::Missing));
  source->waitDelivered();
  s.update(wants, 0.1);
  started = source->started();
  ASSERT_EQ(started.size(), 6u);
  EXPECT_EQ(started[3].path, datasetRelativePath(keys[4], meta()));
  EXPECT_EQ(started[4].path, datasetRelativePath(keys[2], meta()));
  EXPECT_EQ(started[5].path, datasetRelativePath(keys[5], meta()));
  // A new current want while the limit is reached displaces the look-ahead request.
  for (size_t i = 3; i < 5; ++i) source->reply(started[i].id, ScriptedSource::outcome(FetchOutcome::Missing));
  source->waitDelivered();
  s.update(wants, 0.2);  // now: keys[5] and keys[6] (look-ahead) plus one free place
  wants.push_back({keys[7], 1, false});
  const size_t before = source->started().size();
  s.update(wants, 0.3);
  started = source->started();
  ASSERT_GT(started.size(), before);
  EXPECT_EQ(started.back().path, datasetRelativePath(keys[7], meta()));
  EXPECT_EQ(s.state(keys[7]), TileState::Requested);
  EXPECT_EQ(s.frameStats().requestsInFlight, 3u);
}

TEST_F(StreamerScripted, LookAheadRequestMakesRoomForACurrentWant) {
  auto source = std::make_shared<ScriptedSource>();
  StreamingOptions o = smallOptions();
  o.maxRequestsInFlight = 2;
  TileStreamer s(source, meta(), o, makeNullLogger());
  const auto keys = tilesAt(dir(), meta(), TileLayer::Height, meta().maxZoom);
  std::vector<TileWant> wants = {{keys[0], 10, true}, {keys[1], 20, true}};
  s.update(wants, 0.0);
  ASSERT_EQ(source->started().size(), 2u);
  wants.push_back({keys[2], 1, false});
  s.update(wants, 0.1);
  EXPECT_EQ(s.state(keys[2]), TileState::Requested);
  EXPECT_EQ(s.state(keys[0]), TileState::Unloaded);  // the weaker look-ahead request gave way
  EXPECT_EQ(s.state(keys[1]), TileState::Requested);
  EXPECT_EQ(s.frameStats().requestsCancelled, 1u);
  ASSERT_EQ(source->cancels().size(), 1u);
  EXPECT_EQ(source->started()[1].path, datasetRelativePath(keys[0], meta()));  // priority 20 went first
  EXPECT_EQ(source->cancels()[0], source->started()[1].id);
}

TEST_F(StreamerScripted, OkArrivingAfterCancelIsNeverResidentNorUploaded) {
  ManualTaskRunner tasks;
  auto source = std::make_shared<ScriptedSource>();
  source->ignoreCancel = true;  // the answer races the cancellation and wins
  TileStreamer s(source, meta(), smallOptions(&tasks), makeNullLogger());
  const TileKey k = tilesAt(dir(), meta(), TileLayer::Imagery, meta().maxZoom)[0];
  s.update(wantsOf({k}), 0.0);
  ASSERT_EQ(source->started().size(), 1u);
  s.update({}, 0.1);
  EXPECT_EQ(s.frameStats().requestsCancelled, 1u);
  ASSERT_TRUE(
      source->reply(source->started()[0].id, ScriptedSource::ok(fileBytes(dir() / datasetRelativePath(k, meta())))));
  source->waitDelivered();
  EXPECT_EQ(tasks.runAll(), 0u) << "no decode was started for it";
  for (int i = 0; i < 3; ++i) {
    s.update(wantsOf({k}, true), 0.2 + i);  // wanted again, only as look-ahead: a new request
    EXPECT_NE(s.state(k), TileState::ResidentCpu);
    EXPECT_TRUE(s.planUploads().empty());
  }
  EXPECT_EQ(source->started().size(), 2u);
  EXPECT_EQ(s.frameStats().bytesResidentCpu, 0u);
}

TEST_F(StreamerScripted, FailedTemporarilyIsAskedAgainAfterTheBackOff) {
  const TileKey k = tilesAt(dir(), meta(), TileLayer::Height, meta().maxZoom)[0];
  const auto bytes = fileBytes(dir() / datasetRelativePath(k, meta()));
  auto source = std::make_shared<ScriptedSource>([&](const std::string&, int attempt) -> std::optional<FetchResult> {
    return attempt == 1 ? ScriptedSource::outcome(FetchOutcome::Failed, "HTTP 503") : ScriptedSource::ok(bytes);
  });
  ManualTaskRunner tasks;
  StreamingOptions o = smallOptions(&tasks);
  o.failedRetryAfterS = 2.0;
  TileStreamer s(source, meta(), o, makeNullLogger());
  const auto wants = wantsOf({k});
  double t = 0.0;
  s.update(wants, t);
  EXPECT_EQ(s.frameStats().requestsIssued, 1u);
  source->waitDelivered();
  s.update(wants, 0.5);
  EXPECT_EQ(s.state(k), TileState::FailedTemporarily);
  EXPECT_EQ(s.frameStats().requestsFailed, 1u);
  ASSERT_TRUE(s.failure(k));
  EXPECT_NE(s.failure(k)->message.find("HTTP 503"), std::string::npos) << s.failure(k)->message;
  EXPECT_FALSE(s.failure(k)->undecodable);
  s.update(wants, 2.4);  // 1.9 s after the failure: too early
  EXPECT_EQ(s.frameStats().requestsIssued, 0u);
  s.update(wants, 2.6);
  EXPECT_EQ(s.frameStats().requestsIssued, 1u);
  EXPECT_EQ(s.frameStats().retries, 1u);
  t = 2.6;
  ASSERT_TRUE(updateUntil(
      s, wants, t, [&] { return s.state(k) == TileState::ResidentCpu; },
      [&] {
        source->waitDelivered();
        tasks.runAll();
      }));
  EXPECT_EQ(source->started().size(), 2u);
  EXPECT_FALSE(s.failure(k)) << "resident again: the failure is over";
}

// Settling, the streamer's time is the flight time and does not move: a current want that fails
// is asked again at once, up to 3 times in a row, inside the one settle() call; a look-ahead
// want that fails waits for the flight time to pass the back-off.
TEST_F(StreamerScripted, SettleAsksAFailingCurrentWantAgainAtOnceUpToThreeTimes) {
  const auto keys = tilesAt(dir(), meta(), TileLayer::Height, meta().maxZoom);
  const TileKey flaky = keys[0], broken = keys[1], ahead = keys[2];
  const auto bytes = fileBytes(dir() / datasetRelativePath(flaky, meta()));
  auto source =
      std::make_shared<ScriptedSource>([&](const std::string& path, int attempt) -> std::optional<FetchResult> {
        if (path == datasetRelativePath(flaky, meta()) && attempt >= 3) return ScriptedSource::ok(bytes);
        return ScriptedSource::outcome(FetchOutcome::Failed, "HTTP 503");
      });
  StreamingOptions o = smallOptions();  // decodes on a pool of the streamer's own
  o.failedRetryAfterS = 2.0;
  TileStreamer s(source, meta(), o, makeNullLogger());
  const std::vector<TileWant> wants = {{flaky, 2.0, false}, {broken, 1.0, false}, {ahead, 1.0, true}};
  s.settle(wants, 10.0);
  EXPECT_EQ(s.state(flaky), TileState::ResidentCpu);
  EXPECT_EQ(s.state(broken), TileState::FailedTemporarily);
  EXPECT_EQ(s.state(ahead), TileState::FailedTemporarily);
  std::map<std::string, int> starts;
  for (const auto& st : source->started()) ++starts[st.path];
  EXPECT_EQ(starts[datasetRelativePath(flaky, meta())], 3);
  EXPECT_EQ(starts[datasetRelativePath(broken, meta())], 3);
  EXPECT_EQ(starts[datasetRelativePath(ahead, meta())], 1);
  EXPECT_EQ(s.frameStats().retries, 4u);
  EXPECT_EQ(s.frameStats().requestsInFlight, 0u);
  // The next frame, 0.25 s of flight later: the look-ahead tile is not due yet; 2 s later it is.
  s.settle(wants, 10.25);
  EXPECT_EQ(s.frameStats().requestsIssued, 0u);
  s.settle(wants, 12.5);
  EXPECT_EQ(s.frameStats().requestsIssued, 2u) << "broken and ahead, due again by flight time, once each";
}

// A Clock that moves `stepS` every time it is read: with 10 s, settle()'s 30 s bound passes after
// a few reads, without the test waiting 30 s.
class RacingClock final : public Clock {
 public:
  double nowS() const override { return t_ += stepS.load(); }
  std::atomic<double> stepS{10.0};

 private:
  mutable double t_ = 0.0;
};

// A request that never ends: settle() gives up when the injected clock says 30 s passed, and a
// later frame takes the answer in when it comes.
TEST_F(StreamerScripted, SettleGivesUpAfterThirtySecondsOfTheInjectedClock) {
  auto source = std::make_shared<ScriptedSource>();  // holds everything until reply()
  RacingClock clock;
  StreamingOptions o = smallOptions();
  o.clock = &clock;
  TileStreamer s(source, meta(), o, makeNullLogger());
  const TileKey k = tilesAt(dir(), meta(), TileLayer::Height, meta().maxZoom)[0];
  const double waited = s.settle(wantsOf({k}), 0.0);
  EXPECT_GE(waited, 30.0);
  EXPECT_LT(waited, 100.0);
  EXPECT_EQ(s.state(k), TileState::Requested);
  EXPECT_EQ(s.frameStats().requestsInFlight, 1u);
  ASSERT_EQ(source->started().size(), 1u);
  ASSERT_TRUE(
      source->reply(source->started()[0].id, ScriptedSource::ok(fileBytes(dir() / datasetRelativePath(k, meta())))));
  clock.stepS = 0.0;  // this time the wait is not cut short, however slow the decode
  s.settle(wantsOf({k}), 0.25);
  EXPECT_EQ(s.state(k), TileState::ResidentCpu);
  EXPECT_EQ(source->started().size(), 1u) << "not asked twice";
}

// Random outcomes (Ok, Missing, Failed, corrupt bytes) under changing wants: every request is
// accounted for at every frame, and corrupt bytes end Failed.
TEST_F(StreamerScripted, CountersAddUpUnderRandomOutcomes) {
  // Missing and corrupt tiles fail for good, so the pool is every tile of every zoom.
  std::vector<TileKey> keys;
  for (int z = meta().minZoom; z <= meta().maxZoom; ++z)
    for (auto layer : {TileLayer::Height, TileLayer::Imagery})
      for (const auto& k : tilesAt(dir(), meta(), layer, z)) keys.push_back(k);
  std::map<std::string, std::vector<uint8_t>> files;
  for (const auto& k : keys) files[datasetRelativePath(k, meta())] = fileBytes(dir() / datasetRelativePath(k, meta()));
  std::mutex rngMu;
  std::mt19937 outcomes(11);
  auto source = std::make_shared<ScriptedSource>([&](const std::string& path, int) -> std::optional<FetchResult> {
    std::lock_guard lock(rngMu);
    switch (outcomes() % 6) {
      case 0: return ScriptedSource::outcome(FetchOutcome::Missing);
      case 1: return ScriptedSource::outcome(FetchOutcome::Failed);
      case 2: {
        auto b = files.at(path);
        b.resize(b.size() / 3);  // truncated: a decode error
        return ScriptedSource::ok(std::move(b));
      }
      case 3: return std::nullopt;  // held until cancelled
      default: return ScriptedSource::ok(files.at(path));
    }
  });
  ManualTaskRunner tasks;
  StreamingOptions o = smallOptions(&tasks);
  o.failedRetryAfterS = 0.05;
  o.cpuBudgetBytes = 10 * (kTileBytes + 256);
  TileStreamer s(source, meta(), o, makeNullLogger());
  std::mt19937 rng(3);
  Totals totals;
  double t = 0.0;
  for (int round = 0; round < 40; ++round) {
    std::shuffle(keys.begin(), keys.end(), rng);
    const auto n = std::uniform_int_distribution<size_t>(0, 12)(rng);
    std::vector<TileWant> wants;
    for (size_t i = 0; i < n; ++i) wants.push_back({keys[i], double(i), i % 3 == 2});
    // A round lasts until only held requests are under way (or 2000 updates), then the wants
    // change: whatever is held gets cancelled.
    for (int frame = 0; frame < 2000; ++frame) {
      s.update(wants, t);
      t += 0.02;
      totals.add(s.frameStats());
      totals.expectBalanced(s.frameStats());
      ASSERT_LE(s.frameStats().bytesResidentCpu, o.cpuBudgetBytes);
      if (frame > 2 && s.frameStats().decodesQueued == 0 && s.frameStats().requestsInFlight == source->held().size())
        break;
      source->waitDelivered();
      if (frame % 2 == 0) tasks.runAll();  // decodes every other frame: some land a frame late
    }
  }
  s.update({}, t);  // everything still under way is cancelled
  totals.add(s.frameStats());
  totals.expectBalanced(s.frameStats());
  EXPECT_EQ(s.frameStats().requestsInFlight + s.frameStats().decodesQueued, 0u);
  // Every kind of ending happened (the exact sums were checked every frame above).
  EXPECT_GE(totals.completed, 5u);
  EXPECT_GE(totals.failed, 5u);  // Failed answers and corrupt bytes
  EXPECT_GE(totals.missing, 3u);
  EXPECT_GE(totals.cancelled, 5u);
}

}  // namespace
}  // namespace vegstream::streaming::test
