// TileStreamer, resident tiles → GPU slots (tile_streamer_impl.h): the imagery tiles the current
// wants draw with, best first, within the per-frame upload budget; GPU tiles not used this frame
// are evicted (least recently used first) to free slots, which cool down before reuse.

#include <algorithm>

#include "streaming/tile_streamer_impl.h"

namespace vegstream::streaming {

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

}  // namespace vegstream::streaming
