// TileStreamer (tile_streamer.h; README.md has the state diagram). The frame thread owns the
// tile table; the source's threads and the decode threads only talk to it through the
// DecodePipeline's completion queue, which update() drains. So no tile state is ever touched by
// two threads, and update() never waits for more than that queue's mutex.

#include "streaming/tile_streamer.h"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <thread>
#include <unordered_map>
#include <utility>

#include "streaming/decode_pipeline.h"
#include "streaming/gpu_slots.h"

namespace vegstream::streaming {
namespace {

using detail::Completion;

// What a resident tile costs beyond its pixels (the ResidentTile, the shared_ptr blocks, the
// table entry): small, but it keeps "bytes" honest for many tiles.
constexpr uint64_t kTileOverheadBytes = 256;
// A failed tile counts as settled once it failed this many times in a row.
constexpr int kSettleFailures = 3;
constexpr double kSettleTimeoutS = 30.0;

bool isResident(TileState s) {
  return s == TileState::ResidentCpu || s == TileState::Uploading || s == TileState::ResidentGpu;
}
bool isOnGpu(TileState s) { return s == TileState::Uploading || s == TileState::ResidentGpu; }

struct Entry {
  TileState state = TileState::Unloaded;
  RequestId request = 0;                      // Requested / Decoding
  std::shared_ptr<const ResidentTile> tile;   // resident states
  uint64_t lastUsedFrame = 0;                 // LRU recency
  double failedAtS = 0.0;                     // FailedTemporarily: when
  int failures = 0;                           // failed fetches in a row
  double firstWantedS = -1.0;                 // < 0: not a current want
  uint32_t slot = 0;                          // Uploading / ResidentGpu
  bool blockedByBudget = false;               // current want not requested: would not fit
};

struct Want {
  double priority = 0.0;
  bool lookAhead = false;
};

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

struct TileStreamer::Impl {
  std::shared_ptr<TileSource> source;
  datasets::DatasetMeta meta;
  StreamingOptions options;
  Logger log;
  std::unique_ptr<ThreadPool> ownPool;  // when no runner was given (destroyed after the pipeline stops)
  SteadyClock ownClock;                 // when no clock was given
  const Clock* clock;
  std::shared_ptr<detail::DecodePipeline> pipeline;
  std::vector<Completion> heldBack;  // settle(): taken from the pipeline, not yet processed
  detail::GpuSlotAllocator slots;
  uint64_t tileBytesBase;  // what one tile will cost once decoded, before any extra
  uint64_t tileBytesEstimate(const TileKey& key) const {
    return tileBytesBase + (key.layer == TileLayer::Height ? options.heightExtraBytes : 0);
  }

  std::unordered_map<TileKey, Entry, TileKeyHash> table;
  std::unordered_map<RequestId, TileKey> active;  // Requested or Decoding, not cancelled
  std::unordered_map<TileKey, Want, TileKeyHash> wanted;
  std::vector<TileWant> ordered;  // this frame's wants, current first, then priority (deduplicated)
  std::vector<TileKey> residencyChanges;  // since takeResidencyChanges()
  RequestId nextRequest = 0;
  uint64_t frame = 0;
  uint64_t bytesCpu = 0, tilesCpu = 0;
  StreamingFrameStats stats;

  Impl(std::shared_ptr<TileSource> src, datasets::DatasetMeta m, StreamingOptions o, Logger l)
      : source(std::move(src)), meta(std::move(m)), options(o), log(l ? std::move(l) : makeNullLogger()),
        slots(uint32_t(std::min<uint64_t>(o.maxGpuSlots, o.gpuBudgetBytes / kGpuSlotBytes)), o.slotReuseDelayFrames),
        tileBytesBase(uint64_t(m.tileSize) * uint64_t(m.tileSize) * 4 + kTileOverheadBytes) {
    assert(source);
    assert(options.maxRequestsInFlight >= 1);
    clock = options.clock ? options.clock : &ownClock;
    TaskRunner* runner = options.tasks;
    if (!runner) {
      const int threads = options.decodeThreads > 0
                              ? options.decodeThreads
                              : std::max(1, int(std::thread::hardware_concurrency()) - 1);
      ownPool = std::make_unique<ThreadPool>(threads);
      runner = ownPool.get();
    }
    const int decodes = options.decodeThreads > 0 ? options.decodeThreads : std::max(1, runner->concurrency() - 1);
    pipeline = std::make_shared<detail::DecodePipeline>(meta.elevationEncoding, *runner, decodes, options.heightExtra);
  }

  static constexpr uint64_t kGpuSlotBytes = uint64_t(datasets::kTileSize) * datasets::kTileSize * 4;

  bool isCurrentWant(const TileKey& k) const {
    auto it = wanted.find(k);
    return it != wanted.end() && !it->second.lookAhead;
  }

  // ---- wants ---------------------------------------------------------------------------------

  void takeWants(std::span<const TileWant> wants, double timeS) {
    std::unordered_map<TileKey, Want, TileKeyHash> next;
    next.reserve(wants.size());
    for (const auto& w : wants) {
      assert(w.key.layer == TileLayer::Height || meta.imagery.has_value());
      auto [it, fresh] = next.try_emplace(w.key, Want{w.priority, w.lookAhead});
      if (!fresh) {  // the same key twice: the stronger claim wins
        it->second.priority = std::max(it->second.priority, w.priority);
        it->second.lookAhead = it->second.lookAhead && w.lookAhead;
      }
    }
    for (const auto& [key, was] : wanted) {
      auto now = next.find(key);
      auto e = table.find(key);
      if (e == table.end()) continue;
      if (now == next.end() || now->second.lookAhead) {
        e->second.firstWantedS = -1.0;
        e->second.blockedByBudget = false;
      }
      if (now == next.end() && (e->second.state == TileState::Unloaded || e->second.state == TileState::FailedTemporarily))
        table.erase(e);
    }
    wanted = std::move(next);
    ordered.clear();
    for (const auto& [key, w] : wanted) {
      ordered.push_back({key, w.priority, w.lookAhead});
      if (!w.lookAhead) {
        Entry& e = table[key];
        if (e.firstWantedS < 0.0) e.firstWantedS = timeS;
        e.blockedByBudget = false;
        if (isResident(e.state)) e.lastUsedFrame = frame;  // wanted = in use
      }
    }
    std::sort(ordered.begin(), ordered.end(), [](const TileWant& a, const TileWant& b) {
      if (a.lookAhead != b.lookAhead) return !a.lookAhead;
      if (a.priority != b.priority) return a.priority > b.priority;
      return a.key < b.key;  // deterministic order among equals
    });
  }

  // ---- requests ------------------------------------------------------------------------------

  void cancelRequest(RequestId id) {
    auto it = active.find(id);
    assert(it != active.end());
    const TileKey key = it->second;
    active.erase(it);
    Entry& e = table[key];
    const bool atSource = e.state == TileState::Requested;
    e.state = TileState::Unloaded;
    e.request = 0;
    pipeline->cancel(id);               // first: nothing about it reaches the table any more
    if (atSource) source->cancel(id);   // then free the source's worker
    ++stats.requestsCancelled;
    if (!wanted.contains(key)) table.erase(key);
  }

  void cancelUnwanted() {
    std::vector<RequestId> drop;
    for (const auto& [id, key] : active)
      if (!wanted.contains(key)) drop.push_back(id);
    for (RequestId id : drop) cancelRequest(id);
  }

  void issue(const TileKey& key, Entry& e) {
    if (e.state == TileState::FailedTemporarily) ++stats.retries;
    const RequestId id = ++nextRequest;
    e.state = TileState::Requested;
    e.request = id;
    active.emplace(id, key);
    ++stats.requestsIssued;
    std::string path = datasetRelativePath(key, meta);
    source->start(id, path, [pipe = pipeline, key, path](FetchResult&& r) { pipe->onFetched(key, path, std::move(r)); });
  }

  // The look-ahead request of lowest priority, to make room for a current want.
  std::optional<RequestId> weakestLookAheadRequest() const {
    std::optional<RequestId> best;
    double bestPriority = 0.0;
    for (const auto& [id, key] : active) {
      const auto w = wanted.find(key);
      if (w == wanted.end() || !w->second.lookAhead) continue;
      if (!best || w->second.priority < bestPriority) {
        best = id;
        bestPriority = w->second.priority;
      }
    }
    return best;
  }

  void schedule(double timeS, bool settling = false) {
    // Bytes the wants will hold once what is in flight lands: current wants may never be evicted,
    // so a want is requested only if it fits beside them (no request that is sure to be dropped).
    uint64_t currentBytes = 0, allBytes = 0;
    for (const auto& w : ordered) {
      const auto e = table.find(w.key);
      if (e == table.end()) continue;
      const bool holds = isResident(e->second.state) || e->second.state == TileState::Requested ||
                         e->second.state == TileState::Decoding;
      if (!holds) continue;
      const uint64_t b = e->second.tile ? e->second.tile->bytes : tileBytesEstimate(w.key);
      allBytes += b;
      if (!w.lookAhead) currentBytes += b;
    }
    for (const auto& w : ordered) {
      Entry& e = table[w.key];
      // Settling, time stands still: a current want that failed is asked again at once (up to
      // kSettleFailures in a row); look-ahead ones wait for the flight time to pass.
      const bool due = e.state == TileState::Unloaded ||
                       (e.state == TileState::FailedTemporarily &&
                        (timeS - e.failedAtS >= options.failedRetryAfterS ||
                         (settling && !w.lookAhead && e.failures < kSettleFailures)));
      if (!due) continue;
      const uint64_t held = w.lookAhead ? allBytes : currentBytes;
      const uint64_t estimate = tileBytesEstimate(w.key);
      if (held + estimate > options.cpuBudgetBytes) {
        if (!w.lookAhead) {
          e.blockedByBudget = true;
          stats.wantsExceedCpuBudget = true;
        }
        continue;
      }
      if (active.size() >= size_t(options.maxRequestsInFlight)) {
        if (w.lookAhead) break;  // wants are ordered: only look-ahead ones remain
        const auto victim = weakestLookAheadRequest();
        if (!victim) break;
        allBytes -= tileBytesEstimate(active.at(*victim));
        cancelRequest(*victim);
      }
      issue(w.key, e);
      allBytes += estimate;
      if (!w.lookAhead) currentBytes += estimate;
    }
  }

  // ---- completions ---------------------------------------------------------------------------

  void evictCpu(const TileKey& key) {
    auto it = table.find(key);
    assert(it != table.end() && isResident(it->second.state));
    Entry& e = it->second;
    if (isOnGpu(e.state)) {
      slots.release(e.slot, frame);
      ++stats.evictionsGpu;
    }
    bytesCpu -= e.tile->bytes;
    --tilesCpu;
    ++stats.evictionsCpu;
    residencyChanges.push_back(key);
    if (wanted.contains(key)) {  // a look-ahead want: keep the entry, it may be requested again
      e.state = TileState::Unloaded;
      e.tile.reset();
    } else {
      table.erase(it);
    }
  }

  // Evicts least-recently-used tiles until `bytes` more fit. Never a current want, never a GPU
  // tile used this frame; look-ahead wants go after tiles nobody wants. False (nothing evicted)
  // when even that cannot make room.
  bool makeRoom(uint64_t bytes) {
    if (bytesCpu + bytes <= options.cpuBudgetBytes) return true;
    struct Candidate {
      bool lookAhead;
      uint64_t lastUsed;
      double since;
      TileKey key;
      uint64_t bytes;
    };
    std::vector<Candidate> candidates;
    uint64_t freeable = 0;
    for (const auto& [key, e] : table) {
      if (!isResident(e.state) || isCurrentWant(key)) continue;
      if (isOnGpu(e.state) && e.lastUsedFrame == frame) continue;
      candidates.push_back({wanted.contains(key), e.lastUsedFrame, e.tile->residentSinceS, key, e.tile->bytes});
      freeable += e.tile->bytes;
    }
    if (bytesCpu - freeable + bytes > options.cpuBudgetBytes) return false;
    std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
      if (a.lookAhead != b.lookAhead) return !a.lookAhead;
      if (a.lastUsed != b.lastUsed) return a.lastUsed < b.lastUsed;
      if (a.since != b.since) return a.since < b.since;
      return a.key < b.key;
    });
    for (const auto& c : candidates) {
      if (bytesCpu + bytes <= options.cpuBudgetBytes) break;
      evictCpu(c.key);
    }
    return true;
  }

  void admit(const TileKey& key, Completion& c, double timeS) {
    auto tile = std::make_shared<ResidentTile>();
    tile->key = key;
    tile->heights = std::move(c.heights);
    tile->colors = std::move(c.colors);
    tile->extra = std::move(c.extra);
    const uint64_t pixels = tile->heights ? tile->heights->heights.size() * sizeof(float) : tile->colors->rgba.size();
    tile->bytes = pixels + kTileOverheadBytes + (tile->extra ? tile->extra->bytes() : 0);
    tile->residentSinceS = timeS;
    Entry& e = table[key];
    if (!makeRoom(tile->bytes)) {
      // Only the current wants are left and this one does not fit beside them: drop it.
      e.state = TileState::Unloaded;
      ++stats.requestsCancelled;
      if (isCurrentWant(key)) {
        e.blockedByBudget = true;
        stats.wantsExceedCpuBudget = true;
      }
      log->debug("tile {} dropped: it does not fit the CPU budget beside the tiles wanted now", toString(key));
      return;
    }
    e.state = TileState::ResidentCpu;
    e.tile = std::move(tile);
    e.failures = 0;
    e.lastUsedFrame = frame;
    bytesCpu += e.tile->bytes;
    ++tilesCpu;
    ++stats.requestsCompleted;
    residencyChanges.push_back(key);
  }

  // What settle() held back, then what the pipeline has; `inRequestOrder` sorts them by request
  // (stable: a request's Fetched stays before its final completion), so a batch is taken in the
  // same order whatever order the workers finished in.
  void takeCompletions(double timeS, bool inRequestOrder = false) {
    std::vector<Completion> batch = std::exchange(heldBack, {});
    for (Completion& c : pipeline->takeCompletions()) batch.push_back(std::move(c));
    if (inRequestOrder)
      std::stable_sort(batch.begin(), batch.end(), [](const Completion& a, const Completion& b) { return a.id < b.id; });
    for (Completion& c : batch) {
      const auto a = active.find(c.id);
      if (a == active.end()) continue;  // cancelled after the pipeline queued it: dropped
      const TileKey key = a->second;
      Entry& e = table[key];
      assert(e.request == c.id);
      if (c.kind == Completion::Kind::Fetched) {
        stats.bytesRead += c.bytes;
        e.state = TileState::Decoding;
        continue;
      }
      active.erase(a);
      e.request = 0;
      switch (c.kind) {
        case Completion::Kind::Fetched: break;
        case Completion::Kind::Missing:
          e.state = TileState::Failed;
          ++stats.requestsMissing;
          log->debug("tile {} is missing ({}): its parent is drawn", toString(key), c.message);
          break;
        case Completion::Kind::FetchFailed:
          e.state = TileState::FailedTemporarily;
          e.failedAtS = timeS;
          ++e.failures;
          ++stats.requestsFailed;
          log->warn("tile {} failed after {} attempt(s): {}; asking again in {} s", toString(key), c.attempts,
                    c.message, options.failedRetryAfterS);
          break;
        case Completion::Kind::Cancelled:
          e.state = TileState::Unloaded;
          ++stats.requestsCancelled;
          break;
        case Completion::Kind::DecodeFailed:
          e.state = TileState::Failed;
          ++stats.requestsFailed;
          log->warn("tile {} cannot be decoded: {}", toString(key), c.message);
          break;
        case Completion::Kind::Decoded: admit(key, c, timeS); break;
      }
    }
  }

  // ---- lookups -------------------------------------------------------------------------------

  // The key or its nearest ancestor (down to min zoom) whose state passes `accept`.
  template <typename Accept>
  std::pair<Entry*, int> nearest(TileKey key, Accept accept) {
    for (int up = 0;; ++up) {
      auto it = table.find(key);
      if (it != table.end() && accept(it->second.state)) return {&it->second, up};
      if (key.id.z <= meta.minZoom || key.id.z == 0) return {nullptr, 0};
      key = parentOf(key);
    }
  }

  // ---- statistics ----------------------------------------------------------------------------

  void refreshTotals() {
    stats.tilesResidentCpu = tilesCpu;
    stats.bytesResidentCpu = bytesCpu;
    stats.tilesResidentGpu = slots.inUse();
    stats.bytesResidentGpu = uint64_t(slots.inUse()) * kGpuSlotBytes;
  }

  void finishStats(double timeS) {
    stats.requestsInFlight = 0;
    stats.decodesQueued = 0;
    for (const auto& [id, key] : active)
      (table[key].state == TileState::Requested ? stats.requestsInFlight : stats.decodesQueued) += 1;
    for (const auto& w : ordered) {
      if (w.lookAhead) break;
      const Entry& e = table[w.key];
      ++stats.wanted;
      if (isResident(e.state)) ++stats.wantedResident;
      if (e.state != TileState::Failed) stats.wantedBytes += e.tile ? e.tile->bytes : tileBytesEstimate(w.key);
      if (!isResident(e.state) && e.state != TileState::Failed)
        stats.longestWaitS = std::max(stats.longestWaitS, timeS - e.firstWantedS);
    }
    if (stats.wantedBytes > options.cpuBudgetBytes) stats.wantsExceedCpuBudget = true;
    refreshTotals();
    assert(bytesCpu <= options.cpuBudgetBytes);
  }

  // settle(): waits until every request in flight has its final completion (held back, not yet
  // processed); false when `deadlineS` (clock) passed first.
  bool awaitInFlight(double deadlineS) {
    for (;;) {
      for (Completion& c : pipeline->takeCompletions()) heldBack.push_back(std::move(c));
      const size_t finished = size_t(std::count_if(heldBack.begin(), heldBack.end(), [&](const Completion& c) {
        return c.kind != Completion::Kind::Fetched && active.contains(c.id);
      }));
      if (finished >= active.size()) return true;
      if (clock->nowS() > deadlineS) return false;
      (void)pipeline->waitForCompletions(std::chrono::milliseconds(50));
    }
  }

  // Current wants not yet resident, failed or too big (for settle()'s time-out warning).
  size_t currentWantsPending() const {
    size_t n = 0;
    for (const auto& w : ordered) {
      if (w.lookAhead) break;
      const auto it = table.find(w.key);
      const bool done = it != table.end() &&
                        (isResident(it->second.state) || it->second.state == TileState::Failed ||
                         it->second.state == TileState::FailedTemporarily ||
                         (it->second.state == TileState::Unloaded && it->second.blockedByBudget));
      n += done ? 0 : 1;
    }
    return n;
  }
};

TileStreamer::TileStreamer(std::shared_ptr<TileSource> source, datasets::DatasetMeta meta, StreamingOptions options,
                           Logger log)
    : impl_(std::make_unique<Impl>(std::move(source), std::move(meta), options, std::move(log))) {}

TileStreamer::~TileStreamer() {
  // Stop listening first (later callbacks and tasks find the pipeline closed), then free the source.
  impl_->pipeline->stop();
  for (const auto& [id, key] : impl_->active)
    if (impl_->table[key].state == TileState::Requested) impl_->source->cancel(id);
}

const datasets::DatasetMeta& TileStreamer::meta() const { return impl_->meta; }
const StreamingOptions& TileStreamer::options() const { return impl_->options; }
const StreamingFrameStats& TileStreamer::frameStats() const { return impl_->stats; }

bool TileStreamer::waitForArrivals(std::chrono::milliseconds timeout) {
  return impl_->pipeline->waitForCompletions(timeout);
}
uint32_t TileStreamer::gpuSlotCount() const { return impl_->slots.count(); }

void TileStreamer::update(std::span<const TileWant> wants, double timeS) {
  Impl& m = *impl_;
  ++m.frame;
  m.stats = {};
  m.takeWants(wants, timeS);
  m.cancelUnwanted();       // before taking completions: a cancelled tile never becomes resident
  m.takeCompletions(timeS);
  m.schedule(timeS);
  m.finishStats(timeS);
}

std::shared_ptr<const ResidentTile> TileStreamer::get(const TileKey& key) {
  auto it = impl_->table.find(key);
  if (it == impl_->table.end() || !isResident(it->second.state)) return nullptr;
  it->second.lastUsedFrame = impl_->frame;
  return it->second.tile;
}

ResidentLookup TileStreamer::findResident(const TileKey& key) {
  auto [e, up] = impl_->nearest(key, isResident);
  if (!e) return {};
  e->lastUsedFrame = impl_->frame;
  return {e->tile, up};
}

TileStreamer::GpuLookup TileStreamer::findGpuResident(const TileKey& key) {
  auto [e, up] = impl_->nearest(key, [](TileState s) { return s == TileState::ResidentGpu; });
  if (!e) return {};
  e->lastUsedFrame = impl_->frame;
  return {e->tile, e->slot, up};
}

TileState TileStreamer::state(const TileKey& key) const {
  auto it = impl_->table.find(key);
  return it == impl_->table.end() ? TileState::Unloaded : it->second.state;
}

std::vector<Upload> TileStreamer::planUploads(std::optional<uint64_t> byteBudget) {
  Impl& m = *impl_;
  const uint64_t budget = byteBudget.value_or(m.options.uploadBytesPerFrame);
  // The tiles to draw the current imagery wants with, best first; each marked used this frame.
  std::vector<std::pair<TileKey, Entry*>> toUpload;
  for (const auto& w : m.ordered) {
    if (w.lookAhead) break;
    if (w.key.layer != TileLayer::Imagery) continue;
    auto [e, up] = m.nearest(w.key, isResident);
    if (!e) continue;
    e->lastUsedFrame = m.frame;
    if (e->state != TileState::ResidentCpu) continue;
    const TileKey k = e->tile->key;
    if (std::none_of(toUpload.begin(), toUpload.end(), [&](const auto& p) { return p.first == k; }))
      toUpload.emplace_back(k, e);
  }
  const size_t fitBytes = size_t(budget / Impl::kGpuSlotBytes);
  if (toUpload.size() > fitBytes) toUpload.resize(fitBytes);
  // Free slots by evicting GPU tiles not used this frame, least recently used first; evicted
  // slots cool down (slotReuseDelayFrames) before reuse, so count the cooling ones as coming.
  const uint64_t have = uint64_t(m.slots.available(m.frame)) + m.slots.cooling();
  if (toUpload.size() > have) {
    std::vector<std::pair<uint64_t, TileKey>> lru;
    for (const auto& [key, e] : m.table)
      if (isOnGpu(e.state) && e.lastUsedFrame != m.frame) lru.emplace_back(e.lastUsedFrame, key);
    std::sort(lru.begin(), lru.end());
    for (size_t i = 0; i < lru.size() && i < toUpload.size() - have; ++i) {
      Entry& e = m.table[lru[i].second];
      m.slots.release(e.slot, m.frame);
      e.state = TileState::ResidentCpu;
      ++m.stats.evictionsGpu;
    }
  }
  std::vector<Upload> out;
  for (auto& [key, e] : toUpload) {
    const auto slot = m.slots.acquire(m.frame);
    if (!slot) break;
    e->state = TileState::Uploading;
    e->slot = *slot;
    out.push_back({e->tile, *slot});
    m.stats.uploadBytes += Impl::kGpuSlotBytes;
  }
  m.refreshTotals();
  return out;
}

void TileStreamer::uploadsRecorded(std::span<const Upload> uploads) {
  for (const auto& u : uploads) {
    auto it = impl_->table.find(u.tile->key);
    if (it == impl_->table.end()) continue;
    Entry& e = it->second;
    if (e.state == TileState::Uploading && e.slot == u.slot) e.state = TileState::ResidentGpu;
  }
}

namespace {
// The per-frame counters of StreamingFrameStats (the rest are snapshots of the moment).
constexpr uint64_t StreamingFrameStats::*kFrameCounters[] = {
    &StreamingFrameStats::requestsIssued,  &StreamingFrameStats::requestsCompleted,
    &StreamingFrameStats::requestsCancelled, &StreamingFrameStats::requestsFailed,
    &StreamingFrameStats::requestsMissing, &StreamingFrameStats::retries,
    &StreamingFrameStats::bytesRead,       &StreamingFrameStats::uploadBytes,
    &StreamingFrameStats::evictionsCpu,    &StreamingFrameStats::evictionsGpu};
}  // namespace

void addFrameCounters(StreamingFrameStats& into, const StreamingFrameStats& from) {
  for (auto counter : kFrameCounters) into.*counter += from.*counter;
}

void setFrameCounters(StreamingFrameStats& into, const StreamingFrameStats& from) {
  for (auto counter : kFrameCounters) into.*counter = from.*counter;
}

std::vector<TileKey> TileStreamer::takeResidencyChanges() { return std::exchange(impl_->residencyChanges, {}); }

double TileStreamer::settle(std::span<const TileWant> wants, double timeS) {
  Impl& m = *impl_;
  const double start = m.clock->nowS();
  ++m.frame;
  m.stats = {};
  m.takeWants(wants, timeS);
  m.cancelUnwanted();
  // Rounds: everything in flight finishes, its results are taken in request order, the next
  // requests are issued; done when nothing more is in flight. No round reads the clock's time
  // into a tile: timeS alone is the streamer's time.
  for (;;) {
    if (!m.awaitInFlight(start + kSettleTimeoutS)) {
      m.log->warn("settle: {} requests still in flight after {:.0f} s ({} wanted tiles not resident); going on "
                  "without them (this frame and later ones are no longer repeatable)",
                  m.active.size(), kSettleTimeoutS, m.currentWantsPending());
      m.takeCompletions(timeS, true);
      break;
    }
    m.takeCompletions(timeS, true);
    m.schedule(timeS, true);
    if (m.active.empty()) break;
  }
  m.finishStats(timeS);
  return m.clock->nowS() - start;
}

}  // namespace vegstream::streaming
