#pragma once
// InteractionWindow (issue 19, "trails persist"): the CPU's bookkeeping of the GPU interaction
// field's window and of its trail store. It decides every GPU copy and reads nothing back.
//
// The field: windowTiles × windowTiles tiles (16 × 16 of 32 × 32 texels of 0.1 m: 3.2 m, 16 KiB
// each), world-aligned and toroidal around the camera: world tile (x, y) lives in window tile
// windowTileOf((x, y)) = (x mod n) + n · (y mod n), mod never negative. Each texel holds a bend
// direction and a collision strength cs, which falls linearly at recoveryPerS per second to 0.
//
// When the camera moves, the window follows by whole tiles: a tile leaving it hands its window
// tile to the entering tile with the same toroidal index. A leaving tile that still holds a trail
// is copied into the trail store (trail_store.h) first, and copied back when it re-enters.
// "Holds a trail" is known from the colliders alone (markHit): a hit of strength s at time t
// leaves cs ≤ s, gone by t + s / recoveryPerS, and a tile holds a trail until the latest such
// time of the hits on it.
//
// Contract on the GPU side: cs after a hit is at most the hit's strength (a field that adds
// strengths must clamp them, and markHit be given the clamp), and cs never falls slower than
// recoveryPerS; otherwise a tile can be declared recovered while it still shows a trail.
//
// Deterministic: tiles are visited in row-major world order (y, then x), so the same calls give
// the same transfers in the same order.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "simulation/trail_store.h"

namespace vegstream::simulation {

// cs lost per second (cs is normalised: 1 = a fully flattened blade), so a full-strength trail
// lasts 20 s. Placeholder until the interaction pass defines its recovery factor (seed 003
// eq. 47's cr).
inline constexpr double kDefaultRecoveryPerS = 0.05;

// One GPU copy of a frame.
struct TileTransfer {
  enum class Kind {
    Save,     // window tile → store slot (before the tile is overwritten by the entering one)
    Restore,  // store slot → window tile, then decay cs by recoveryPerS · elapsedS
    Clear,    // window tile → no bend, cs 0
  };
  Kind kind = Kind::Clear;
  uint32_t windowTile = 0;  // windowTileOf(key)
  uint32_t storeSlot = 0;   // Save, Restore: the store's slot; 0 for Clear
  double elapsedS = 0.0;    // Restore: time since the tile was saved (the decay it missed); else 0
  TileKey key;              // the world tile saved (the leaving one) or written (the entering one)
};

struct InteractionWindowOptions {
  int windowTiles = 16;                        // tiles along a side (> 0)
  double tileM = 3.2;                          // a tile's side (32 texels of 0.1 m)
  double recoveryPerS = kDefaultRecoveryPerS;  // cr (> 0): the slowest the GPU lets cs fall
  uint64_t storeBytes = uint64_t{16} << 20;    // the trail store's budget (the 16 MB default)
  uint64_t tileBytes = 16384;                  // one tile in the store: 32 · 32 texels × 16 bytes (> 0)
};

class InteractionWindow {
 public:
  // The store gets floor(storeBytes / tileBytes) slots; fewer than one tile's bytes give 0 slots:
  // trails are simply lost when their tile leaves (valid, not an error).
  explicit InteractionWindow(const InteractionWindowOptions& options);

  // Centres the window on the camera (local metres; timeS never decreasing): origin tile =
  // floor(camera / tileM) − windowTiles / 2 on each axis. Returns this frame's GPU transfers, to
  // be run in order: every Save first (a leaving tile's window tile is reused by the entering
  // tile with the same toroidal index), then the entering tiles' Restores and Clears. The first
  // call returns a Clear for every window tile. No Restore reads a slot a Save of the same frame
  // writes.
  //   - A leaving tile holding a trail at timeS is saved (into a free slot, else the least
  //     recently seen stored tile's: TrailStore::save); one without a trail is left to be
  //     overwritten.
  //   - An entering tile in the store is restored (elapsedS = timeS − its save time), its slot
  //     freed, and it holds its trail again until its old time; a stored tile whose trail ran
  //     out meanwhile has been forgotten, and an entering tile not in the store is cleared.
  std::vector<TileTransfer> update(double cameraX, double cameraY, double timeS);

  // A collider touched the world box [minX, maxX] × [minY, maxY] at timeS with `strength` (≥ 0,
  // the most cs it can leave): every window tile overlapping the box holds a trail until at
  // least timeS + strength / recoveryPerS. Tiles outside the window are not in the field and are
  // ignored. Only after the first update().
  void markHit(double minX, double minY, double maxX, double maxY, double timeS, double strength);

  TileKey originTile() const { return origin_; }
  // Until when the window's tile `key` holds a trail (≤ now: none). Tiles outside the window
  // (stored or not) give −∞.
  double trailUntil(TileKey key) const;
  static uint32_t windowTileOf(TileKey key, int windowTiles);

  std::size_t storedTiles() const { return store_.size(); }  // tiles in the store now
  uint64_t storeBytesUsed() const { return uint64_t{store_.size()} * options_.tileBytes; }
  uint32_t storeSlots() const { return store_.capacity(); }  // its capacity
  uint64_t evictions() const { return store_.evictions(); }  // trails lost for lack of room

 private:
  bool inWindow(TileKey key, TileKey origin) const;
  TileKey tileAt(double x, double y) const;

  InteractionWindowOptions options_;
  TrailStore store_;
  std::vector<double> trailUntil_;  // per window tile: its tile's trail end (−∞: clean)
  TileKey origin_;
  double nowS_ = 0.0;
  bool started_ = false;
};

}  // namespace vegstream::simulation
