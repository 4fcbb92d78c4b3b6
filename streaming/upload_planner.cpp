// UploadPlanner (upload_planner.h): the imagery tiles the current wants draw with, best first,
// within the per-frame upload budget; GPU tiles not used this frame are evicted (least recently
// used first) to free slots, which cool down before reuse.

#include "streaming/upload_planner.h"

#include <algorithm>

namespace vegstream::streaming::detail {

UploadPlanner::UploadPlanner(TileTable& table, const StreamingOptions& options, StreamingFrameStats& stats)
    : table_(table), stats_(stats),
      slots_(uint32_t(std::min<uint64_t>(options.maxGpuSlots, options.gpuBudgetBytes / kGpuSlotBytes)),
             options.slotReuseDelayFrames) {}

std::vector<std::pair<TileKey, Entry*>> UploadPlanner::tilesToUpload() {
  std::vector<std::pair<TileKey, Entry*>> toUpload;
  for (const auto& w : table_.ordered()) {
    if (w.lookAhead) break;
    if (w.key.layer != TileLayer::Imagery) continue;
    auto [e, up] = table_.nearest(w.key, isResident);
    if (!e) continue;
    e->lastUsedFrame = table_.frame();
    if (e->state != TileState::ResidentCpu) continue;
    const TileKey k = e->tile->key;
    if (std::none_of(toUpload.begin(), toUpload.end(), [&](const auto& p) { return p.first == k; }))
      toUpload.emplace_back(k, e);
  }
  return toUpload;
}

void UploadPlanner::freeSlots(size_t needed) {
  // Evicted slots cool down (slotReuseDelayFrames) before reuse, so count the cooling ones as coming.
  const uint64_t have = uint64_t(slots_.available(table_.frame())) + slots_.cooling();
  if (needed <= have) return;
  std::vector<std::pair<uint64_t, TileKey>> lru;
  for (const auto& [key, e] : table_.entries())
    if (isOnGpu(e.state) && e.lastUsedFrame != table_.frame()) lru.emplace_back(e.lastUsedFrame, key);
  std::sort(lru.begin(), lru.end());
  for (size_t i = 0; i < lru.size() && i < needed - have; ++i) {
    Entry& e = table_.entry(lru[i].second);
    release(e);
    e.state = TileState::ResidentCpu;
  }
}

std::vector<Upload> UploadPlanner::plan(uint64_t byteBudget) {
  std::vector<std::pair<TileKey, Entry*>> toUpload = tilesToUpload();
  const size_t fitBytes = size_t(byteBudget / kGpuSlotBytes);
  if (toUpload.size() > fitBytes) toUpload.resize(fitBytes);
  freeSlots(toUpload.size());
  std::vector<Upload> out;
  for (auto& [key, e] : toUpload) {
    const auto slot = slots_.acquire(table_.frame());
    if (!slot) break;
    e->state = TileState::Uploading;
    e->slot = *slot;
    out.push_back({e->tile, *slot});
    stats_.uploadBytes += kGpuSlotBytes;
  }
  return out;
}

void UploadPlanner::recorded(std::span<const Upload> uploads) {
  for (const auto& u : uploads) {
    Entry* e = table_.find(u.tile->key);
    if (!e) continue;
    if (e->state == TileState::Uploading && e->slot == u.slot) e->state = TileState::ResidentGpu;
  }
}

void UploadPlanner::release(const Entry& e) {
  slots_.release(e.slot, table_.frame());
  ++stats_.evictionsGpu;
}

void UploadPlanner::countTotals(StreamingFrameStats& stats) const {
  stats.tilesResidentGpu = slots_.inUse();
  stats.bytesResidentGpu = uint64_t(slots_.inUse()) * kGpuSlotBytes;
}

}  // namespace vegstream::streaming::detail
