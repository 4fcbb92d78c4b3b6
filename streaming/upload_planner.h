#pragma once
// UploadPlanner (internal to the streamer, tile_streamer.h): resident imagery tiles → layers
// of the renderer's imagery array. It owns the GPU slots (gpu_slots.h:
// min(maxGpuSlots, gpuBudgetBytes / kGpuSlotBytes) of them, each freed slot cooling down
// slotReuseDelayFrames before reuse) and moves entries between ResidentCpu, Uploading and
// ResidentGpu.
//
// Contract (README "Budgets and eviction", GPU):
//   - plan(): for each current imagery want in order, its nearest CPU-resident ancestor-or-self
//     (marked used this frame) not yet on the GPU, once each, within the byte budget; when the
//     slots are short, GPU tiles not used this frame are evicted (least recently used first,
//     back to ResidentCpu); the chosen tiles → Uploading, each with a slot.
//   - recorded(): the renderer recorded those copies → ResidentGpu.
//   - release(): a tile on the GPU leaves the CPU (tile_residency.h): its slot cools down.
// Counts uploadBytes and evictionsGpu into the frame's figures.

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "datasets/dataset_format.h"
#include "streaming/gpu_slots.h"
#include "streaming/tile_streamer.h"
#include "streaming/tile_table.h"

namespace vegstream::streaming::detail {

// One layer of the imagery array: an RGBA tile.
constexpr uint64_t kGpuSlotBytes = uint64_t(datasets::kTileSize) * datasets::kTileSize * 4;

class UploadPlanner {
 public:
  // Every reference outlives the planner.
  UploadPlanner(TileTable& table, const StreamingOptions& options, StreamingFrameStats& stats);

  std::vector<Upload> plan(uint64_t byteBudget);
  void recorded(std::span<const Upload> uploads);
  // `e` (Uploading or ResidentGpu) leaves the GPU with the CPU; its state is the caller's.
  void release(const Entry& e);

  uint32_t slotCount() const { return slots_.count(); }
  // tilesResidentGpu and bytesResidentGpu.
  void countTotals(StreamingFrameStats& stats) const;

 private:
  // The tiles to draw the current imagery wants with, best first; each marked used this frame.
  std::vector<std::pair<TileKey, Entry*>> tilesToUpload();
  // Evicts GPU tiles not used this frame, least recently used first, until `needed` slots are
  // free or cooling.
  void freeSlots(size_t needed);

  TileTable& table_;
  StreamingFrameStats& stats_;
  GpuSlotAllocator slots_;
};

}  // namespace vegstream::streaming::detail
