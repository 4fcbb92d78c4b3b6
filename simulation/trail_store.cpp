// The trail store's slot pool (see the header).
#include "simulation/trail_store.h"

#include <cassert>

namespace vegstream::simulation {

TrailStore::TrailStore(uint32_t slots) : capacity_(slots) {}

std::optional<uint32_t> TrailStore::freeSlot() {
  if (!free_.empty()) {
    const uint32_t s = free_.back();
    free_.pop_back();
    return s;
  }
  if (nextFresh_ < capacity_) return nextFresh_++;
  return std::nullopt;
}

void TrailStore::erase(std::map<TileKey, Stored>::iterator it) {
  bySaveOrder_.erase(it->second.order);
  byRecovery_.erase({it->second.entry.recoveredAtS, it->first});
  entries_.erase(it);
}

std::optional<uint32_t> TrailStore::save(TileKey key, double nowS, double recoveredAtS) {
  assert(!entries_.contains(key) && "a tile in the store is outside the window: it cannot leave it again");
  assert(recoveredAtS > nowS && "a recovered tile has nothing to keep");
  std::optional<uint32_t> slot = freeSlot();
  if (!slot) {
    // Full: the least recently seen tile makes room, unless it left in this same frame (equally
    // recent, and its save is already planned into the slot) or nothing is stored at all.
    const auto oldest = bySaveOrder_.begin();
    if (oldest == bySaveOrder_.end() || !(entries_.at(oldest->second).entry.savedAtS < nowS)) {
      ++evictions_;
      return std::nullopt;
    }
    const auto victim = entries_.find(oldest->second);
    slot = victim->second.entry.slot;
    erase(victim);
    ++evictions_;
  }
  const uint64_t order = nextOrder_++;
  entries_.emplace(key, Stored{Entry{*slot, nowS, recoveredAtS}, order});
  bySaveOrder_.emplace(order, key);
  byRecovery_.emplace(recoveredAtS, key);
  return slot;
}

std::optional<TrailStore::Entry> TrailStore::take(TileKey key) {
  const auto it = entries_.find(key);
  if (it == entries_.end()) return std::nullopt;
  const Entry e = it->second.entry;
  erase(it);
  return e;
}

void TrailStore::release(uint32_t slot) {
  assert(slot < nextFresh_ && "only a slot handed out by take() is released");
  free_.push_back(slot);
}

void TrailStore::dropRecovered(double nowS) {
  while (!byRecovery_.empty() && byRecovery_.begin()->first <= nowS) {
    const auto it = entries_.find(byRecovery_.begin()->second);
    assert(it != entries_.end());
    const uint32_t slot = it->second.entry.slot;
    erase(it);
    free_.push_back(slot);
  }
}

const TrailStore::Entry* TrailStore::find(TileKey key) const {
  const auto it = entries_.find(key);
  return it == entries_.end() ? nullptr : &it->second.entry;
}

}  // namespace vegstream::simulation
