// TileStreamer (tile_streamer.h; README.md has the state diagram). The frame thread owns the
// tile table; the source's threads and the decode threads only talk to it through the
// DecodePipeline's completion queue, which update() drains. So no tile state is ever touched by
// two threads, and update() never waits for more than that queue's mutex.
//
// The streamer is the owner of its parts and says in which order they run; each part owns its
// own state:
//   TileTable         tile_table.h         the entries, this frame's wants in order, the LRU frame
//   RequestScheduler  request_scheduler.h  wants → requests: cancelling, scheduling under budgets
//   CompletionIntake  completion_intake.h  completions → tile states (held back while settling)
//   TileResidency     tile_residency.h     the CPU budget: admission, LRU eviction
//   UploadPlanner     upload_planner.h     GPU slots: upload planning, GPU eviction

#include "streaming/tile_streamer.h"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <thread>
#include <utility>

#include "streaming/completion_intake.h"
#include "streaming/decode_pipeline.h"
#include "streaming/request_scheduler.h"
#include "streaming/tile_residency.h"
#include "streaming/tile_table.h"
#include "streaming/upload_planner.h"

namespace vegstream::streaming {

namespace {

// settle() gives up waiting for what is in flight after this long (clock), with a warning.
constexpr double kSettleTimeoutS = 30.0;

// The per-frame counters of StreamingFrameStats (the rest are snapshots of the moment).
constexpr uint64_t StreamingFrameStats::*kFrameCounters[] = {
    &StreamingFrameStats::requestsIssued,    &StreamingFrameStats::requestsCompleted,
    &StreamingFrameStats::requestsCancelled, &StreamingFrameStats::requestsFailed,
    &StreamingFrameStats::requestsMissing,   &StreamingFrameStats::retries,
    &StreamingFrameStats::bytesRead,         &StreamingFrameStats::uploadBytes,
    &StreamingFrameStats::evictionsCpu,      &StreamingFrameStats::evictionsGpu};

// The decode pipeline, on `options.tasks` or else on a pool of the streamer's own (`ownPool`).
std::shared_ptr<detail::DecodePipeline> makePipeline(const datasets::DatasetMeta& meta, const StreamingOptions& options,
                                                     std::unique_ptr<ThreadPool>& ownPool) {
  TaskRunner* runner = options.tasks;
  if (!runner) {
    const int threads =
        options.decodeThreads > 0 ? options.decodeThreads : std::max(1, int(std::thread::hardware_concurrency()) - 1);
    ownPool = std::make_unique<ThreadPool>(threads);
    runner = ownPool.get();
  }
  const int decodes = options.decodeThreads > 0 ? options.decodeThreads : std::max(1, runner->concurrency() - 1);
  return std::make_shared<detail::DecodePipeline>(meta.elevationEncoding, meta.tileSize, *runner, decodes,
                                                  options.heightExtra);
}

}  // namespace

const char* toString(TileState s) {
  switch (s) {
    case TileState::Unloaded: return "unloaded";
    case TileState::Requested: return "requested";
    case TileState::Decoding: return "decoding";
    case TileState::ResidentCpu: return "resident-cpu";
    case TileState::Uploading: return "uploading";
    case TileState::ResidentGpu: return "resident-gpu";
    case TileState::FailedTemporarily: return "failed-temporarily";
    case TileState::Failed: return "failed";
  }
  return "?";
}

void addFrameCounters(StreamingFrameStats& into, const StreamingFrameStats& from) {
  for (auto counter : kFrameCounters) into.*counter += from.*counter;
}

void setFrameCounters(StreamingFrameStats& into, const StreamingFrameStats& from) {
  for (auto counter : kFrameCounters) into.*counter = from.*counter;
}

struct TileStreamer::Impl {
  std::shared_ptr<TileSource> source;
  datasets::DatasetMeta meta;
  StreamingOptions options;
  Logger log;
  std::unique_ptr<ThreadPool> ownPool;  // when no runner was given (destroyed after the pipeline stops)
  SteadyClock ownClock;                 // when no clock was given
  const Clock* clock;
  std::shared_ptr<detail::DecodePipeline> pipeline;
  StreamingFrameStats stats;  // the last update()'s figures, counted into by every part
  detail::TileTable table;
  detail::UploadPlanner uploads;
  detail::TileResidency residency;
  detail::RequestScheduler requests;
  detail::CompletionIntake completions;

  Impl(std::shared_ptr<TileSource> src, datasets::DatasetMeta m, StreamingOptions o, Logger l)
      : source(std::move(src)), meta(std::move(m)), options(o), log(l ? std::move(l) : makeNullLogger()),
        clock(options.clock ? options.clock : &ownClock), pipeline(makePipeline(meta, options, ownPool)),
        table(meta, options.heightExtraBytes), uploads(table, options, stats),
        residency(table, uploads, options, stats, log), requests(table, *source, pipeline, meta, options, stats),
        completions(*pipeline, table, requests, residency, options, stats, log) {
    assert(source);
    assert(options.maxRequestsInFlight >= 1);
  }

  // The frame's figures once its requests are scheduled.
  void finishStats(double timeS) {
    requests.countInFlight(stats);
    table.countWants(stats, timeS);
    if (stats.wantedBytes > options.cpuBudgetBytes) stats.wantsExceedCpuBudget = true;
    refreshTotals();
    assert(residency.bytes() <= options.cpuBudgetBytes);
  }

  void refreshTotals() {
    residency.countTotals(stats);
    uploads.countTotals(stats);
  }
};

TileStreamer::TileStreamer(std::shared_ptr<TileSource> source, datasets::DatasetMeta meta, StreamingOptions options,
                           Logger log)
    : impl_(std::make_unique<Impl>(std::move(source), std::move(meta), options, std::move(log))) {}

TileStreamer::~TileStreamer() {
  // Stop listening first (later callbacks and tasks find the pipeline closed), then free the source.
  impl_->pipeline->stop();
  impl_->requests.cancelAtSource();
}

const datasets::DatasetMeta& TileStreamer::meta() const { return impl_->meta; }
const StreamingOptions& TileStreamer::options() const { return impl_->options; }
const StreamingFrameStats& TileStreamer::frameStats() const { return impl_->stats; }

bool TileStreamer::waitForArrivals(std::chrono::milliseconds timeout) {
  return impl_->pipeline->waitForCompletions(timeout);
}
TileStreamer::IoProgress TileStreamer::ioProgress() const {
  return {impl_->source->inFlight(), impl_->source->counters(), impl_->pipeline->decodesQueued()};
}
uint32_t TileStreamer::gpuSlotCount() const { return impl_->uploads.slotCount(); }

void TileStreamer::update(std::span<const TileWant> wants, double timeS) {
  Impl& m = *impl_;
  m.table.nextFrame();
  m.stats = {};
  m.table.takeWants(wants, timeS);
  m.requests.cancelUnwanted();  // before taking completions: a cancelled tile never becomes resident
  m.completions.take(timeS);
  m.requests.schedule(timeS);
  m.finishStats(timeS);
}

double TileStreamer::settle(std::span<const TileWant> wants, double timeS) {
  Impl& m = *impl_;
  const double start = m.clock->nowS();
  m.table.nextFrame();
  m.stats = {};
  m.table.takeWants(wants, timeS);
  m.requests.cancelUnwanted();
  // Rounds: everything in flight finishes, its results are taken in request order, the next
  // requests are issued; done when nothing more is in flight. No round reads the clock's time
  // into a tile: timeS alone is the streamer's time.
  for (;;) {
    if (!m.completions.awaitInFlight(*m.clock, start + kSettleTimeoutS)) {
      m.log->warn(
          "settle: {} requests still in flight after {:.0f} s ({} wanted tiles not resident); going on "
          "without them (this frame and later ones are no longer repeatable)",
          m.requests.inFlight(), kSettleTimeoutS, m.table.currentWantsPending());
      m.completions.take(timeS, true);
      break;
    }
    m.completions.take(timeS, true);
    m.requests.schedule(timeS, true);
    if (m.requests.inFlight() == 0) break;
  }
  m.finishStats(timeS);
  return m.clock->nowS() - start;
}

std::shared_ptr<const ResidentTile> TileStreamer::get(const TileKey& key) {
  detail::Entry* e = impl_->table.find(key);
  if (!e || !detail::isResident(e->state)) return nullptr;
  e->lastUsedFrame = impl_->table.frame();
  return e->tile;
}

ResidentLookup TileStreamer::findResident(const TileKey& key) {
  auto [e, up] = impl_->table.nearest(key, detail::isResident);
  if (!e) return {};
  e->lastUsedFrame = impl_->table.frame();
  return {e->tile, up};
}

TileStreamer::GpuLookup TileStreamer::findGpuResident(const TileKey& key) {
  auto [e, up] = impl_->table.nearest(key, [](TileState s) { return s == TileState::ResidentGpu; });
  if (!e) return {};
  e->lastUsedFrame = impl_->table.frame();
  return {e->tile, e->slot, up};
}

std::optional<TileStreamer::Failure> TileStreamer::failure(const TileKey& key) const {
  const detail::Entry* e = impl_->table.find(key);
  if (!e) return std::nullopt;
  return e->state == TileState::Failed || e->state == TileState::FailedTemporarily ? e->failure : std::nullopt;
}

TileState TileStreamer::state(const TileKey& key) const { return impl_->table.state(key); }

std::vector<Upload> TileStreamer::planUploads(std::optional<uint64_t> byteBudget) {
  std::vector<Upload> out = impl_->uploads.plan(byteBudget.value_or(impl_->options.uploadBytesPerFrame));
  impl_->refreshTotals();
  return out;
}

void TileStreamer::uploadsRecorded(std::span<const Upload> uploads) { impl_->uploads.recorded(uploads); }

std::vector<TileKey> TileStreamer::takeResidencyChanges() { return impl_->residency.takeChanges(); }

}  // namespace vegstream::streaming
