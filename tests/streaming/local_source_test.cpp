// LocalTileSource over a real dataset directory: whole files, Missing, paths outside the
// dataset, cancellation of queued requests, shutdown with requests queued, counters; and the
// in-memory decoders it feeds (corrupt and truncated bytes are errors naming the tile).
// The reads run on a ManualTaskRunner the test steps, or wait on a condition: nothing sleeps.

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstring>
#include <fstream>
#include <future>
#include <iterator>
#include <map>
#include <mutex>
#include <thread>

#include "core/task_runner.h"
#include "datasets/tile_codec.h"
#include "streaming/local_tile_source.h"
#include "streaming_fixture.h"

namespace vegstream::streaming::test {
namespace {

std::vector<uint8_t> fileBytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Collects callbacks; counts how often each id was called back.
struct Answers {
  std::mutex mu;
  std::condition_variable cv;
  std::map<RequestId, FetchResult> results;
  std::map<RequestId, int> calls;

  FetchCallback callback() {
    return [this](FetchResult&& r) {
      std::lock_guard lock(mu);
      ++calls[r.id];
      results[r.id] = std::move(r);
      cv.notify_all();
    };
  }
  bool waitFor(size_t n, std::chrono::milliseconds limit = std::chrono::seconds(10)) {
    std::unique_lock lock(mu);
    return cv.wait_for(lock, limit, [&] { return results.size() >= n; });
  }
};

using LocalSource = SyntheticDataset;

TEST_F(LocalSource, ReadsWholeFilesAndReportsMissingAndBadPaths) {
  ManualTaskRunner tasks;
  LocalTileSource source(dir(), 2, &tasks);
  EXPECT_EQ(source.describe(), "dir " + dir().string());
  const auto keys = tilesAt(dir(), meta(), TileLayer::Height, meta().maxZoom);
  const std::string path = datasetRelativePath(keys[0], meta());
  Answers a;
  source.start(1, path, a.callback());
  source.start(2, "elevation/14/1/1.png", a.callback());
  source.start(3, "../outside.png", a.callback());
  source.start(4, "/etc/passwd", a.callback());
  source.start(5, "elevation", a.callback());  // a directory
  EXPECT_TRUE(a.results.empty()) << "answered by the runner's tasks, never inside start()";
  EXPECT_EQ(tasks.pending(), 2u) << "at most ioConcurrency tasks at once";
  EXPECT_EQ(tasks.runAll(), 6u) << "one request a task run (the last run finds the queue empty)";
  ASSERT_TRUE(a.waitFor(5));
  EXPECT_EQ(a.results[1].outcome, FetchOutcome::Ok);
  EXPECT_EQ(a.results[1].bytes, fileBytes(dir() / path));
  EXPECT_EQ(a.results[1].attempts, 1);
  EXPECT_EQ(a.results[2].outcome, FetchOutcome::Missing);
  EXPECT_NE(a.results[2].message.find("elevation/14/1/1.png"), std::string::npos) << a.results[2].message;
  EXPECT_EQ(a.results[3].outcome, FetchOutcome::Failed);
  EXPECT_EQ(a.results[4].outcome, FetchOutcome::Failed);
  EXPECT_EQ(a.results[5].outcome, FetchOutcome::Failed);
  for (const auto& [id, n] : a.calls) EXPECT_EQ(n, 1) << id;
  const auto c = source.counters();
  EXPECT_EQ(c.requestsStarted, 5u);
  EXPECT_EQ(c.requestsCompleted, 1u);
  EXPECT_EQ(c.requestsMissing, 1u);
  EXPECT_EQ(c.requestsFailed, 3u);
  EXPECT_EQ(c.bytesRead, a.results[1].bytes.size());
  EXPECT_EQ(source.inFlight(), 0u);
}

TEST_F(LocalSource, ReadTextReadsDatasetJson) {
  LocalTileSource source(dir());
  auto text = source.readText("dataset.json");
  ASSERT_TRUE(text) << text.error().message;
  EXPECT_NE(text->find("\"synthetic\""), std::string::npos);
  auto missing = source.readText("nope.json");
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().kind, ErrorKind::NotFound);
  EXPECT_NE(missing.error().message.find("nope.json"), std::string::npos);
  EXPECT_FALSE(source.readText("../dataset.json"));
}

// One I/O thread held inside the first callback: the other requests are queued for certain,
// and cancelling them ends them Cancelled without a read.
TEST_F(LocalSource, CancelledQueuedRequestsEndCancelled) {
  LocalTileSource source(dir(), 1);
  const auto keys = tilesAt(dir(), meta(), TileLayer::Imagery, meta().maxZoom);
  std::promise<void> release;
  std::shared_future<void> gate = release.get_future().share();
  Answers a;
  auto inner = a.callback();
  source.start(100, datasetRelativePath(keys[0], meta()), [&, gate](FetchResult&& r) {
    gate.wait();
    inner(std::move(r));
  });
  for (RequestId id = 1; id <= 10; ++id)
    source.start(id, datasetRelativePath(keys[id % keys.size()], meta()), a.callback());
  for (RequestId id = 2; id <= 10; id += 2) source.cancel(id);
  source.cancel(999);  // unknown: ignored
  release.set_value();
  ASSERT_TRUE(a.waitFor(11));
  EXPECT_EQ(a.results[100].outcome, FetchOutcome::Ok);
  for (RequestId id = 1; id <= 10; ++id) {
    EXPECT_EQ(a.results[id].outcome, id % 2 == 0 ? FetchOutcome::Cancelled : FetchOutcome::Ok) << id;
    EXPECT_EQ(a.calls[id], 1);
  }
  const auto c = source.counters();
  EXPECT_EQ(c.requestsCancelled, 5u);
  EXPECT_EQ(c.requestsCompleted, 6u);
}

// The first request is read; the source goes with 20 still queued: the destructor answers them
// Cancelled, and the task still posted, run afterwards, finds nothing to do.
TEST_F(LocalSource, DestructorEndsQueuedRequestsCancelled) {
  Answers a;
  const auto keys = tilesAt(dir(), meta(), TileLayer::Height, meta().maxZoom);
  ManualTaskRunner tasks;
  {
    LocalTileSource source(dir(), 1, &tasks);
    source.start(100, datasetRelativePath(keys[0], meta()), a.callback());
    for (RequestId id = 1; id <= 20; ++id)
      source.start(id, datasetRelativePath(keys[id % keys.size()], meta()), a.callback());
    ASSERT_TRUE(tasks.runOne());
    EXPECT_EQ(a.results.size(), 1u);
    EXPECT_EQ(tasks.pending(), 1u) << "the task posted itself again";
  }
  EXPECT_EQ(a.results.size(), 21u);
  EXPECT_EQ(tasks.runAll(), 1u);
  ASSERT_EQ(a.results.size(), 21u);
  EXPECT_EQ(a.results[100].outcome, FetchOutcome::Ok);
  for (RequestId id = 1; id <= 20; ++id) {
    EXPECT_EQ(a.calls[id], 1);
    EXPECT_EQ(a.results[id].outcome, FetchOutcome::Cancelled) << id;
  }
}

// Over a real pool the destructor waits for a read under way: a callback held while the
// source is being destroyed still arrives exactly once, before the destructor returns, and
// every queued request is answered too (read or cancelled, depending on whether the destructor
// had begun when the callback returned — the test cannot tell, so it accepts both).
TEST_F(LocalSource, DestructorWaitsForTheReadUnderWay) {
  Answers a;
  const auto keys = tilesAt(dir(), meta(), TileLayer::Height, meta().maxZoom);
  ThreadPool pool(2);
  std::promise<void> entered;
  std::promise<void> release;
  std::shared_future<void> gate = release.get_future().share();
  auto source = std::make_unique<LocalTileSource>(dir(), 1, &pool);
  auto inner = a.callback();
  source->start(100, datasetRelativePath(keys[0], meta()), [&entered, inner, gate](FetchResult&& r) mutable {
    entered.set_value();
    gate.wait();
    inner(std::move(r));
  });
  for (RequestId id = 1; id <= 5; ++id)
    source->start(id, datasetRelativePath(keys[id % keys.size()], meta()), a.callback());
  entered.get_future().wait();  // the read of 100 is under way, inside its callback
  std::thread destroyer([&source] { source.reset(); });
  release.set_value();
  destroyer.join();
  ASSERT_EQ(a.results.size(), 6u) << "everything answered before the destructor returned";
  EXPECT_EQ(a.results[100].outcome, FetchOutcome::Ok);
  for (RequestId id = 1; id <= 5; ++id) {
    EXPECT_EQ(a.calls[id], 1) << id;
    EXPECT_TRUE(a.results[id].outcome == FetchOutcome::Ok || a.results[id].outcome == FetchOutcome::Cancelled) << id;
  }
}

// ---- the decoders the streamer's workers run ----

using TileDecode = SyntheticDataset;

TEST_F(TileDecode, FromMemoryEqualsFromFile) {
  const auto k = tilesAt(dir(), meta(), TileLayer::Height, meta().maxZoom)[0];
  const fs::path file = dir() / datasetRelativePath(k, meta());
  auto a = datasets::decodeHeightTile(fileBytes(file), k.id, meta().elevationEncoding, datasets::kTileSize, "x");
  auto b = datasets::readHeightTile(file, k.id, meta().elevationEncoding, datasets::kTileSize);
  ASSERT_TRUE(a) << a.error().message;
  ASSERT_TRUE(b);
  EXPECT_EQ(a->size, 256);
  EXPECT_EQ(a->id, k.id);
  ASSERT_EQ(a->heights.size(), b->heights.size());
  EXPECT_EQ(0, std::memcmp(a->heights.data(), b->heights.data(), a->heights.size() * sizeof(float)));
}

TEST_F(TileDecode, CorruptOrTruncatedBytesAreInvalidInputNamingTheTile) {
  const auto k = tilesAt(dir(), meta(), TileLayer::Imagery, meta().maxZoom)[0];
  auto png = fileBytes(dir() / datasetRelativePath(k, meta()));
  // A JPEG of our own, written by the codec.
  datasets::ColorTile c;
  c.rgba.assign(256 * 256 * 4, 200);
  const fs::path jpegFile = testTmp("decode") / "t.jpg";
  fs::create_directories(jpegFile.parent_path());
  ASSERT_TRUE(datasets::writeColorTile(jpegFile, c, datasets::ImageryFormat::Jpeg));
  auto jpeg = fileBytes(jpegFile);
  ASSERT_TRUE(datasets::decodeColorTile(jpeg, {}, datasets::kTileSize, "t.jpg"));

  const std::string name = "imagery/14/1/2.png";
  std::vector<std::vector<uint8_t>> bad;
  bad.emplace_back(png.begin(), png.begin() + std::ptrdiff_t(png.size() / 2));  // truncated PNG
  auto flipped = png;
  flipped[png.size() / 2] ^= 0x5a;  // CRC failure
  bad.push_back(flipped);
  bad.emplace_back(jpeg.begin(), jpeg.begin() + 40);  // JPEG cut inside its headers
  bad.push_back({'n', 'o', 't', ' ', 'a', 'n', ' ', 'i', 'm', 'a', 'g', 'e'});
  bad.push_back({});
  for (size_t i = 0; i < bad.size(); ++i) {
    auto r = datasets::decodeColorTile(bad[i], {}, datasets::kTileSize, name);
    ASSERT_FALSE(r) << "case " << i;
    EXPECT_EQ(r.error().kind, ErrorKind::InvalidInput) << i;
    EXPECT_NE(r.error().message.find(name), std::string::npos) << r.error().message;
    auto h = datasets::decodeHeightTile(bad[i], {}, meta().elevationEncoding, datasets::kTileSize, name);
    EXPECT_FALSE(h) << "case " << i;
  }
  fs::remove_all(jpegFile.parent_path());
}

}  // namespace
}  // namespace vegstream::streaming::test
