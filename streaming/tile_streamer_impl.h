#pragma once
// TileStreamer's inside (private to streaming/: only the tile_*.cpp files that implement
// tile_streamer.h include it). The tile table and its entries, and the one struct the parts of
// the streamer share, split by concern:
//   tile_streamer.cpp  the public calls: update, lookups, construction and shutdown
//   tile_requests.cpp  wants → requests: ordering, cancelling, scheduling under the budgets
//   tile_residency.cpp completions → resident tiles: admission, LRU eviction, frame figures
//   tile_uploads.cpp   resident tiles → GPU slots: upload planning and GPU eviction
//   tile_settle.cpp    settled frames: every request in flight finishes, taken in request order

#include <algorithm>
#include <cassert>
#include <cstdint>
#include <memory>
#include <optional>
#include <unordered_map>
#include <span>
#include <thread>
#include <utility>
#include <vector>

#include "streaming/decode_pipeline.h"
#include "streaming/gpu_slots.h"
#include "streaming/tile_streamer.h"

namespace vegstream::streaming {
namespace detail {

// What a resident tile costs beyond its pixels (the ResidentTile, the shared_ptr blocks, the
// table entry): small, but it keeps "bytes" honest for many tiles.
constexpr uint64_t kTileOverheadBytes = 256;
// A failed tile counts as settled once it failed this many times in a row.
constexpr int kSettleFailures = 3;
constexpr double kSettleTimeoutS = 30.0;

inline bool isResident(TileState s) {
  return s == TileState::ResidentCpu || s == TileState::Uploading || s == TileState::ResidentGpu;
}
inline bool isOnGpu(TileState s) { return s == TileState::Uploading || s == TileState::ResidentGpu; }

struct Entry {
  TileState state = TileState::Unloaded;
  RequestId request = 0;                         // Requested / Decoding
  std::shared_ptr<const ResidentTile> tile;      // resident states
  uint64_t lastUsedFrame = 0;                    // LRU recency
  double failedAtS = 0.0;                        // FailedTemporarily: when
  int failures = 0;                              // failed fetches in a row
  double firstWantedS = -1.0;                    // < 0: not a current want
  uint32_t slot = 0;                             // Uploading / ResidentGpu
  bool blockedByBudget = false;                  // current want not requested: would not fit
  std::optional<TileStreamer::Failure> failure;  // the last failure (Failed / FailedTemporarily)
};

struct Want {
  double priority = 0.0;
  bool lookAhead = false;
};

}  // namespace detail

using detail::Completion;
using detail::Entry;
using detail::isOnGpu;
using detail::isResident;
using detail::kSettleFailures;
using detail::kSettleTimeoutS;
using detail::kTileOverheadBytes;
using detail::Want;

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
  std::vector<TileWant> ordered;          // this frame's wants, current first, then priority (deduplicated)
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
      const int threads =
          options.decodeThreads > 0 ? options.decodeThreads : std::max(1, int(std::thread::hardware_concurrency()) - 1);
      ownPool = std::make_unique<ThreadPool>(threads);
      runner = ownPool.get();
    }
    const int decodes = options.decodeThreads > 0 ? options.decodeThreads : std::max(1, runner->concurrency() - 1);
    pipeline = std::make_shared<detail::DecodePipeline>(meta.elevationEncoding, meta.tileSize, *runner, decodes,
                                                        options.heightExtra);
  }

  static constexpr uint64_t kGpuSlotBytes = uint64_t(datasets::kTileSize) * datasets::kTileSize * 4;

  bool isCurrentWant(const TileKey& k) const {
    auto it = wanted.find(k);
    return it != wanted.end() && !it->second.lookAhead;
  }

  // ---- wants ---------------------------------------------------------------------------------

  void takeWants(std::span<const TileWant> wants, double timeS);

  // ---- requests ------------------------------------------------------------------------------

  void cancelRequest(RequestId id);

  void cancelUnwanted();

  void issue(const TileKey& key, Entry& e);

  // The look-ahead request of lowest priority, to make room for a current want.
  std::optional<RequestId> weakestLookAheadRequest() const;

  void schedule(double timeS, bool settling = false);

  // ---- completions ---------------------------------------------------------------------------

  void evictCpu(const TileKey& key);

  // Evicts least-recently-used tiles until `bytes` more fit. Never a current want, never a GPU
  // tile used this frame; look-ahead wants go after tiles nobody wants. False (nothing evicted)
  // when even that cannot make room.
  bool makeRoom(uint64_t bytes);

  void admit(const TileKey& key, Completion& c, double timeS);

  // What settle() held back, then what the pipeline has; `inRequestOrder` sorts them by request
  // (stable: a request's Fetched stays before its final completion), so a batch is taken in the
  // same order whatever order the workers finished in.
  void takeCompletions(double timeS, bool inRequestOrder = false);

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

  void refreshTotals();

  void finishStats(double timeS);

  // settle(): waits until every request in flight has its final completion (held back, not yet
  // processed); false when `deadlineS` (clock) passed first.
  bool awaitInFlight(double deadlineS);

  // Current wants not yet resident, failed or too big (for settle()'s time-out warning).
  size_t currentWantsPending() const;
};

}  // namespace vegstream::streaming
