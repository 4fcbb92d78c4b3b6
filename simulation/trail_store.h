#pragma once
// TrailStore: which interaction-field tiles sit in the trail store (issue 19), the GPU pool of
// tile slots that keeps trails alive while their tiles are outside the interaction window
// (interaction_window.h). This is the CPU's bookkeeping only: the GPU copies tiles in and out of
// the slots it hands out, and nothing is ever read back.
//
// A slot holds one tile. The pool has a fixed number of slots (floor(budget / tile bytes); 0 is
// valid: nothing is kept). A full pool makes room by evicting the least recently seen tile: the
// one that left the window earliest. A stored tile is not seen again until it is taken back out,
// so "least recently seen" is "saved first" and the eviction order is the save order.
//
// take() hands a tile's slot to the caller without freeing it; release() frees it. The frame
// that restores a tile from a slot orders its saves before its restores, so it must not save
// another tile into that slot: the slot stays out of the pool until the frame is planned.
//
// Deterministic: ordered containers only, slots handed out lowest-first and then most recently
// freed first, so the same calls give the same slots.

#include <compare>
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <utility>
#include <vector>

namespace vegstream::simulation {

// A world tile of the interaction field: floor(world metres / tile size) on each axis.
struct TileKey {
  int32_t x = 0, y = 0;
  auto operator<=>(const TileKey&) const = default;
};

class TrailStore {
 public:
  struct Entry {
    uint32_t slot = 0;
    double savedAtS = 0.0;      // when it left the window: the last time it was seen
    double recoveredAtS = 0.0;  // when its trail is gone (collision strength 0 everywhere)
  };

  explicit TrailStore(uint32_t slots);

  // Keeps `key` (not stored now), which leaves the window at nowS with a trail until
  // recoveredAtS (> nowS). Returns the slot the GPU copies it into. When no slot is free, the
  // least recently seen stored tile is evicted and its slot reused — unless it was saved at
  // nowS too (the same frame: its save would be overwritten) or there is none (0 slots, or all
  // taken and not released): then `key` itself is dropped and nullopt returned. Either way a
  // trail is lost: evictions() counts both.
  std::optional<uint32_t> save(TileKey key, double nowS, double recoveredAtS);

  // Takes `key` out of the store: its entry, or nullopt if it is not stored. The entry's slot
  // stays out of the pool until release(slot).
  std::optional<Entry> take(TileKey key);
  // Frees a slot handed out by take().
  void release(uint32_t slot);

  // Forgets the tiles whose trails are gone by nowS (recoveredAtS <= nowS): there is nothing
  // left to restore, and their slots are free again. Not evictions.
  void dropRecovered(double nowS);

  // The entry of `key`, or nullptr if it is not stored.
  const Entry* find(TileKey key) const;
  std::size_t size() const { return entries_.size(); }
  uint32_t capacity() const { return capacity_; }
  // Trails lost for lack of room so far (see save()).
  uint64_t evictions() const { return evictions_; }

 private:
  struct Stored {
    Entry entry;
    uint64_t order = 0;  // save order: the key of bySaveOrder_
  };
  void erase(std::map<TileKey, Stored>::iterator it);
  std::optional<uint32_t> freeSlot();

  uint32_t capacity_;
  uint32_t nextFresh_ = 0;      // slots below it have been handed out at least once
  std::vector<uint32_t> free_;  // freed slots, reused last-freed first
  std::map<TileKey, Stored> entries_;
  std::map<uint64_t, TileKey> bySaveOrder_;          // first: least recently seen
  std::set<std::pair<double, TileKey>> byRecovery_;  // first: the next trail to be gone
  uint64_t nextOrder_ = 0;
  uint64_t evictions_ = 0;
};

}  // namespace vegstream::simulation
