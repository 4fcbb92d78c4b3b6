#pragma once
// TileResidency (internal to the streamer, tile_streamer.h): the CPU side of the resident
// tiles. It owns what they count against cpuBudgetBytes (tiles and bytes) and the keys that
// became CPU-resident or left the CPU since the terrain last asked (takeChanges).
//
// Contract (README "Budgets and eviction", CPU):
//   - admit(): a decoded tile costs its pixels + kTileOverheadBytes (+ its extra); room is made
//     by evicting resident tiles nobody wants before look-ahead wants, then least recently used,
//     then oldest, never a current want, never a GPU tile used this frame. If even that cannot
//     make room the tile is dropped (Unloaded, counted as cancelled; a current want is marked
//     blocked by the budget). Otherwise it becomes ResidentCpu, used this frame.
//   - A tile evicted from the CPU leaves the GPU too (upload_planner.h); a look-ahead want
//     keeps its entry (Unloaded), any other tile leaves the table.
//   - After every admit, bytes() ≤ cpuBudgetBytes.
// Counts requestsCompleted, requestsCancelled (dropped) and evictionsCpu into the frame's figures.

#include <cstdint>
#include <utility>
#include <vector>

#include "core/log.h"
#include "streaming/decode_pipeline.h"
#include "streaming/tile_key.h"
#include "streaming/tile_streamer.h"
#include "streaming/tile_table.h"

namespace vegstream::streaming::detail {

class UploadPlanner;

class TileResidency {
 public:
  // Every reference outlives the residency.
  TileResidency(TileTable& table, UploadPlanner& gpu, const StreamingOptions& options, StreamingFrameStats& stats,
                const Logger& log);

  // The decoded tile of `c` (kind Decoded) for `key`, at update() time `timeS`.
  void admit(const TileKey& key, Completion& c, double timeS);

  uint64_t bytes() const { return bytesCpu_; }
  // tilesResidentCpu and bytesResidentCpu.
  void countTotals(StreamingFrameStats& stats) const;
  // Keys that became CPU-resident or left the CPU since the last call, in that order.
  std::vector<TileKey> takeChanges() { return std::exchange(changes_, {}); }

 private:
  // Evicts least-recently-used tiles until `bytes` more fit (the order above). False (nothing
  // evicted) when even that cannot make room.
  bool makeRoom(uint64_t bytes);
  void evict(const TileKey& key);

  TileTable& table_;
  UploadPlanner& gpu_;
  const StreamingOptions& options_;
  StreamingFrameStats& stats_;
  const Logger& log_;
  uint64_t bytesCpu_ = 0, tilesCpu_ = 0;
  std::vector<TileKey> changes_;
};

}  // namespace vegstream::streaming::detail
