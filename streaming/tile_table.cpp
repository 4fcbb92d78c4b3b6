// TileTable (tile_table.h): the tile entries and this frame's wants in a fixed order (current
// first, then priority, then key), so that everything the streamer does in order — requests,
// uploads, settled rounds — comes out the same for the same wants.

#include "streaming/tile_table.h"

#include <algorithm>
#include <cassert>

namespace vegstream::streaming::detail {

TileTable::TileTable(const datasets::DatasetMeta& meta, uint64_t heightExtraBytes)
    : minZoom_(meta.minZoom), hasImagery_(meta.imagery.has_value()),
      tileBytesBase_(uint64_t(meta.tileSize) * uint64_t(meta.tileSize) * 4 + kTileOverheadBytes),
      heightExtraBytes_(heightExtraBytes) {}

void TileTable::takeWants(std::span<const TileWant> wants, double timeS) {
  std::unordered_map<TileKey, Want, TileKeyHash> next;
  next.reserve(wants.size());
  for (const auto& w : wants) {
    assert(w.key.layer == TileLayer::Height || hasImagery_);
    auto [it, fresh] = next.try_emplace(w.key, Want{w.priority, w.lookAhead});
    if (!fresh) {  // the same key twice: the stronger claim wins
      it->second.priority = std::max(it->second.priority, w.priority);
      it->second.lookAhead = it->second.lookAhead && w.lookAhead;
    }
  }
  for (const auto& [key, was] : wanted_) {
    auto now = next.find(key);
    auto e = entries_.find(key);
    if (e == entries_.end()) continue;
    if (now == next.end() || now->second.lookAhead) {
      e->second.firstWantedS = -1.0;
      e->second.blockedByBudget = false;
    }
    if (now == next.end() &&
        (e->second.state == TileState::Unloaded || e->second.state == TileState::FailedTemporarily))
      entries_.erase(e);
  }
  wanted_ = std::move(next);
  ordered_.clear();
  for (const auto& [key, w] : wanted_) {
    ordered_.push_back({key, w.priority, w.lookAhead});
    if (!w.lookAhead) {
      Entry& e = entries_[key];
      if (e.firstWantedS < 0.0) e.firstWantedS = timeS;
      e.blockedByBudget = false;
      if (isResident(e.state)) e.lastUsedFrame = frame_;  // wanted = in use
    }
  }
  std::sort(ordered_.begin(), ordered_.end(), [](const TileWant& a, const TileWant& b) {
    if (a.lookAhead != b.lookAhead) return !a.lookAhead;
    if (a.priority != b.priority) return a.priority > b.priority;
    return a.key < b.key;  // deterministic order among equals
  });
}

const Want* TileTable::want(const TileKey& key) const {
  const auto it = wanted_.find(key);
  return it == wanted_.end() ? nullptr : &it->second;
}

bool TileTable::isCurrentWant(const TileKey& key) const {
  const Want* w = want(key);
  return w && !w->lookAhead;
}

Entry* TileTable::find(const TileKey& key) {
  auto it = entries_.find(key);
  return it == entries_.end() ? nullptr : &it->second;
}

const Entry* TileTable::find(const TileKey& key) const {
  auto it = entries_.find(key);
  return it == entries_.end() ? nullptr : &it->second;
}

TileState TileTable::state(const TileKey& key) const {
  const Entry* e = find(key);
  return e ? e->state : TileState::Unloaded;
}

void TileTable::countWants(StreamingFrameStats& stats, double timeS) {
  for (const auto& w : ordered_) {
    if (w.lookAhead) break;
    const Entry& e = entries_[w.key];
    ++stats.wanted;
    if (isResident(e.state)) ++stats.wantedResident;
    if (e.state != TileState::Failed) stats.wantedBytes += e.tile ? e.tile->bytes : bytesEstimate(w.key);
    if (!isResident(e.state) && e.state != TileState::Failed)
      stats.longestWaitS = std::max(stats.longestWaitS, timeS - e.firstWantedS);
  }
}

size_t TileTable::currentWantsPending() const {
  size_t n = 0;
  for (const auto& w : ordered_) {
    if (w.lookAhead) break;
    const Entry* e = find(w.key);
    const bool done =
        e && (isResident(e->state) || e->state == TileState::Failed || e->state == TileState::FailedTemporarily ||
              (e->state == TileState::Unloaded && e->blockedByBudget));
    n += done ? 0 : 1;
  }
  return n;
}

}  // namespace vegstream::streaming::detail
