#pragma once
// TileTable (internal to the streamer, tile_streamer.h): the one table of tiles the streamer
// knows, touched on the frame thread only. It owns
//   - an Entry per tile that is wanted, in flight, resident or failed (state, request, resident
//     tile, LRU recency, failures; README "Tile states"), and when an entry leaves it;
//   - this frame's wants: each key's claim (priority, look-ahead) and the wants in a fixed order
//     (current first, then priority, larger first, then key), deduplicated;
//   - the frame number, the LRU clock that `lastUsedFrame` is read against;
//   - what a tile will cost against the CPU budget once decoded (for budgets before it is).
// The other parts of the streamer (request_scheduler.h, tile_residency.h, upload_planner.h,
// completion_intake.h) change entries' states through it; it decides nothing about requests,
// budgets or slots.

#include <cstdint>
#include <optional>
#include <span>
#include <unordered_map>
#include <utility>
#include <vector>

#include "datasets/dataset_format.h"
#include "streaming/tile_key.h"
#include "streaming/tile_source.h"
#include "streaming/tile_streamer.h"

namespace vegstream::streaming::detail {

// What a resident tile costs beyond its pixels (the ResidentTile, the shared_ptr blocks, the
// table entry): small, but it keeps "bytes" honest for many tiles.
constexpr uint64_t kTileOverheadBytes = 256;

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

class TileTable {
 public:
  TileTable(const datasets::DatasetMeta& meta, uint64_t heightExtraBytes);

  // The LRU clock: one step per update() or settle().
  uint64_t frame() const { return frame_; }
  void nextFrame() { ++frame_; }

  // This frame's wants (update() step 1). A key no longer wanted stops being a current want
  // (its wait and budget flag reset); one that is also Unloaded or FailedTemporarily leaves the
  // table. Every current want gets an entry; a resident one is marked used this frame.
  void takeWants(std::span<const TileWant> wants, double timeS);
  // This frame's wants, deduplicated, current first, then priority (larger first), then key.
  std::span<const TileWant> ordered() const { return ordered_; }
  const Want* want(const TileKey& key) const;
  bool isWanted(const TileKey& key) const { return wanted_.contains(key); }
  bool isCurrentWant(const TileKey& key) const;

  Entry* find(const TileKey& key);
  const Entry* find(const TileKey& key) const;
  // The key's entry, made Unloaded if it has none.
  Entry& entry(const TileKey& key) { return entries_[key]; }
  void erase(const TileKey& key) { entries_.erase(key); }
  TileState state(const TileKey& key) const;
  // Every entry, in the table's own order (callers that pick among them sort what they pick).
  const std::unordered_map<TileKey, Entry, TileKeyHash>& entries() const { return entries_; }

  // The key or its nearest ancestor (down to min zoom) whose state passes `accept`, with how
  // many levels up it is; {nullptr, 0} if none.
  template <typename Accept>
  std::pair<Entry*, int> nearest(TileKey key, Accept accept) {
    for (int up = 0;; ++up) {
      auto it = entries_.find(key);
      if (it != entries_.end() && accept(it->second.state)) return {&it->second, up};
      if (key.id.z <= minZoom_ || key.id.z == 0) return {nullptr, 0};
      key = parentOf(key);
    }
  }

  // What the tile will count against the CPU budget once decoded, before any is.
  uint64_t bytesEstimate(const TileKey& key) const {
    return tileBytesBase_ + (key.layer == TileLayer::Height ? heightExtraBytes_ : 0);
  }

  // The current wants' figures: wanted, wantedResident, wantedBytes, longestWaitS.
  void countWants(StreamingFrameStats& stats, double timeS);
  // Current wants not yet resident, failed or too big (for settle()'s time-out warning).
  size_t currentWantsPending() const;

 private:
  std::unordered_map<TileKey, Entry, TileKeyHash> entries_;
  std::unordered_map<TileKey, Want, TileKeyHash> wanted_;
  std::vector<TileWant> ordered_;
  uint64_t frame_ = 0;
  int minZoom_;
  [[maybe_unused]] bool hasImagery_;  // checked against the wants (asserts)
  uint64_t tileBytesBase_;            // one decoded tile's pixels and overhead
  uint64_t heightExtraBytes_;         // StreamingOptions::heightExtraBytes
};

}  // namespace vegstream::streaming::detail
