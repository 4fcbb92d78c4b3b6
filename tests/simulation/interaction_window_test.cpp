// simulation/interaction_window.h, simulation/trail_store.h: the interaction field's window
// moves by whole tiles, leaving trails go to the trail store and come back from the slot they
// were saved into, and the store stays inside its budget.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <iterator>
#include <map>
#include <ostream>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "simulation/interaction_window.h"

namespace vegstream::simulation {

void PrintTo(const TileKey& k, std::ostream* os) { *os << "(" << k.x << ", " << k.y << ")"; }

namespace {

using Kind = TileTransfer::Kind;
constexpr double kTileM = 3.2;
constexpr uint64_t kTileBytes = 16384;

InteractionWindowOptions withSlots(uint64_t slots, uint64_t extraBytes = 0) {
  InteractionWindowOptions o;
  o.storeBytes = slots * kTileBytes + extraBytes;
  return o;
}

std::vector<TileTransfer> ofKind(const std::vector<TileTransfer>& t, Kind kind) {
  std::vector<TileTransfer> out;
  std::copy_if(t.begin(), t.end(), std::back_inserter(out), [&](const TileTransfer& x) { return x.kind == kind; });
  return out;
}

// A hit inside one tile (its centre ± 0.1 m).
void hitTile(InteractionWindow& w, TileKey k, double timeS, double strength) {
  const double cx = (k.x + 0.5) * kTileM, cy = (k.y + 0.5) * kTileM;
  w.markHit(cx - 0.1, cy - 0.1, cx + 0.1, cy + 0.1, timeS, strength);
}

std::vector<uint32_t> sortedWindowTiles(const std::vector<TileTransfer>& t) {
  std::vector<uint32_t> out;
  for (const TileTransfer& x : t) out.push_back(x.windowTile);
  std::sort(out.begin(), out.end());
  return out;
}

TEST(InteractionWindow, FirstUpdateClearsAll256WindowTiles) {
  InteractionWindow w(InteractionWindowOptions{});
  EXPECT_EQ(w.storeSlots(), 1024u);  // 16 MiB / 16 KiB
  const std::vector<TileTransfer> t = w.update(-0.1, 5.0, 0.0);
  // floor(-0.1 / 3.2) − 8 = −9, floor(5 / 3.2) − 8 = −7.
  EXPECT_EQ(w.originTile(), (TileKey{-9, -7}));
  ASSERT_EQ(t.size(), 256u);
  std::vector<int> written(256, 0);
  for (const TileTransfer& x : t) {
    EXPECT_EQ(x.kind, Kind::Clear);
    EXPECT_EQ(x.windowTile, InteractionWindow::windowTileOf(x.key, 16));
    EXPECT_TRUE(x.key.x >= -9 && x.key.x <= 6 && x.key.y >= -7 && x.key.y <= 8);
    ++written[x.windowTile];
  }
  for (int n : written) EXPECT_EQ(n, 1);
  EXPECT_EQ(t.front().key, (TileKey{-9, -7}));  // row-major: y, then x
  EXPECT_EQ(t[1].key, (TileKey{-8, -7}));
  EXPECT_EQ(t.back().key, (TileKey{6, 8}));
  // Moving inside the same tile changes nothing.
  EXPECT_TRUE(w.update(-3.0, 5.5, 0.5).empty());
  EXPECT_EQ(w.storedTiles(), 0u);
}

TEST(InteractionWindow, OneTileEastSavesOnlyTheDirtyLeavingTilesAndClearsTheEntering16) {
  InteractionWindow w(InteractionWindowOptions{});
  (void)w.update(1.0, 1.0, 0.0);  // origin (−8, −8): x −8 … 7
  ASSERT_EQ(w.originTile(), (TileKey{-8, -8}));
  // Two tiles of the leaving column x = −8 (rows 0 and 1) by one box; a stale trail in the same
  // column (gone at 1.2 s); one trail that stays in the window.
  w.markHit(-25.5, 0.5, -25.0, 3.5, 1.0, 0.5);  // until 1 + 0.5 / 0.05 = 11 s
  hitTile(w, {-8, -7}, 1.0, 0.01);
  hitTile(w, {0, 0}, 1.0, 1.0);
  EXPECT_DOUBLE_EQ(w.trailUntil({-8, 0}), 11.0);
  EXPECT_DOUBLE_EQ(w.trailUntil({-8, 1}), 11.0);
  EXPECT_DOUBLE_EQ(w.trailUntil({-8, 2}), -INFINITY);

  const std::vector<TileTransfer> t = w.update(4.0, 1.0, 2.0);
  EXPECT_EQ(w.originTile(), (TileKey{-7, -8}));
  ASSERT_EQ(t.size(), 18u);
  EXPECT_EQ(t[0].kind, Kind::Save);
  EXPECT_EQ(t[0].key, (TileKey{-8, 0}));
  EXPECT_EQ(t[0].windowTile, 8u);  // −8 mod 16 = 8, row 0
  EXPECT_EQ(t[0].storeSlot, 0u);
  EXPECT_EQ(t[1].kind, Kind::Save);
  EXPECT_EQ(t[1].key, (TileKey{-8, 1}));
  EXPECT_EQ(t[1].windowTile, 24u);
  EXPECT_EQ(t[1].storeSlot, 1u);
  for (size_t i = 2; i < t.size(); ++i) {
    const int y = -8 + int(i) - 2;
    EXPECT_EQ(t[i].kind, Kind::Clear) << i;
    EXPECT_EQ(t[i].key, (TileKey{8, y}));
    EXPECT_EQ(t[i].windowTile, uint32_t(8 + 16 * ((y + 16) % 16)));  // the column the leaving tiles had
  }
  EXPECT_EQ(w.storedTiles(), 2u);
  EXPECT_EQ(w.storeBytesUsed(), 2 * kTileBytes);
  EXPECT_EQ(w.evictions(), 0u);
  EXPECT_DOUBLE_EQ(w.trailUntil({0, 0}), 21.0);
  EXPECT_DOUBLE_EQ(w.trailUntil({-8, 0}), -INFINITY);  // outside now
  EXPECT_DOUBLE_EQ(w.trailUntil({8, 0}), -INFINITY);   // entered clean
}

TEST(InteractionWindow, TrailLeftFor200mComesBackFromItsSlotWithTheElapsedTime) {
  InteractionWindow w(InteractionWindowOptions{});
  (void)w.update(1.0, 1.0, 0.0);
  w.markHit(7.0, 10.0, 7.5, 10.5, 0.5, 1.0);  // tile (2, 3), until 20.5 s
  const TileKey trail{2, 3};
  const uint32_t windowTile = 2 + 16 * 3;

  const std::vector<TileTransfer> away = w.update(201.0, 1.0, 1.0);
  EXPECT_EQ(w.originTile(), (TileKey{54, -8}));  // every tile left
  ASSERT_EQ(away.size(), 1u + 256u);
  EXPECT_EQ(away[0].kind, Kind::Save);
  EXPECT_EQ(away[0].key, trail);
  EXPECT_EQ(away[0].windowTile, windowTile);
  const uint32_t slot = away[0].storeSlot;
  EXPECT_EQ(ofKind(away, Kind::Clear).size(), 256u);
  EXPECT_EQ(w.storedTiles(), 1u);
  EXPECT_TRUE(w.update(200.5, 1.0, 6.0).empty());  // still tile 62

  const std::vector<TileTransfer> back = w.update(1.0, 1.0, 11.0);
  ASSERT_EQ(back.size(), 256u);  // nothing was dirty over there: no saves
  const std::vector<TileTransfer> restores = ofKind(back, Kind::Restore);
  ASSERT_EQ(restores.size(), 1u);
  EXPECT_EQ(restores[0].key, trail);
  EXPECT_EQ(restores[0].storeSlot, slot);
  EXPECT_EQ(restores[0].windowTile, windowTile);
  EXPECT_DOUBLE_EQ(restores[0].elapsedS, 10.0);
  EXPECT_EQ(ofKind(back, Kind::Clear).size(), 255u);
  EXPECT_EQ(w.storedTiles(), 0u);
  // It holds its trail again, until the old time: leaving again saves it again.
  EXPECT_DOUBLE_EQ(w.trailUntil(trail), 20.5);
  const std::vector<TileTransfer> again = w.update(201.0, 1.0, 12.0);
  ASSERT_EQ(ofKind(again, Kind::Save).size(), 1u);
  EXPECT_EQ(again[0].key, trail);
}

TEST(InteractionWindow, RecoveredTrailIsNotSavedNorRestored) {
  auto withTrail = [] {
    InteractionWindow w(InteractionWindowOptions{});
    (void)w.update(1.0, 1.0, 0.0);
    hitTile(w, {0, 0}, 0.0, 0.5);  // until 10 s
    return w;
  };
  InteractionWindow recovered = withTrail();
  EXPECT_TRUE(ofKind(recovered.update(201.0, 1.0, 10.0), Kind::Save).empty());  // cs reached 0 at 10 s
  EXPECT_EQ(recovered.storedTiles(), 0u);

  InteractionWindow dirty = withTrail();
  EXPECT_EQ(ofKind(dirty.update(201.0, 1.0, 9.5), Kind::Save).size(), 1u);
  EXPECT_EQ(dirty.storedTiles(), 1u);
  // Its trail runs out in the store: forgotten (slot freed), and cleared when it comes back.
  EXPECT_TRUE(dirty.update(201.0, 1.0, 10.0).empty());
  EXPECT_EQ(dirty.storedTiles(), 0u);
  const std::vector<TileTransfer> back = dirty.update(1.0, 1.0, 30.0);
  EXPECT_TRUE(ofKind(back, Kind::Restore).empty());
  EXPECT_EQ(ofKind(back, Kind::Clear).size(), 256u);
}

TEST(InteractionWindow, FullStoreOf2EvictsTheLeastRecentlySeenOf3Trails) {
  InteractionWindow w(withSlots(2, kTileBytes - 1));
  EXPECT_EQ(w.storeSlots(), 2u);
  (void)w.update(1.0, 1.0, 0.0);                            // x −8 … 7
  for (int x : {-8, -7, -6}) hitTile(w, {x, 0}, 0.0, 1.0);  // until 20 s
  // One tile east per second: column −8 leaves at 1 s, −7 at 2 s, −6 at 3 s.
  std::vector<TileTransfer> saves;
  for (int step = 1; step <= 3; ++step) {
    const std::vector<TileTransfer> t = w.update(1.0 + step * kTileM, 1.0, step);
    for (const TileTransfer& s : ofKind(t, Kind::Save)) saves.push_back(s);
  }
  ASSERT_EQ(saves.size(), 3u);
  EXPECT_EQ(saves[0].key, (TileKey{-8, 0}));
  EXPECT_EQ(saves[0].storeSlot, 0u);
  EXPECT_EQ(saves[1].key, (TileKey{-7, 0}));
  EXPECT_EQ(saves[1].storeSlot, 1u);
  EXPECT_EQ(saves[2].key, (TileKey{-6, 0}));
  EXPECT_EQ(saves[2].storeSlot, 0u);  // (−8, 0), seen last at 1 s, made room
  EXPECT_EQ(w.evictions(), 1u);
  EXPECT_EQ(w.storedTiles(), 2u);
  EXPECT_EQ(w.storeBytesUsed(), 2 * kTileBytes);

  const std::vector<TileTransfer> back = w.update(1.0, 1.0, 4.0);
  EXPECT_EQ(back.size(), 48u);  // three columns enter; the leaving ones are clean
  const std::vector<TileTransfer> restores = ofKind(back, Kind::Restore);
  ASSERT_EQ(restores.size(), 2u);
  EXPECT_EQ(restores[0].key, (TileKey{-7, 0}));  // row-major order
  EXPECT_EQ(restores[0].storeSlot, 1u);
  EXPECT_DOUBLE_EQ(restores[0].elapsedS, 2.0);
  EXPECT_EQ(restores[1].key, (TileKey{-6, 0}));
  EXPECT_EQ(restores[1].storeSlot, 0u);
  EXPECT_DOUBLE_EQ(restores[1].elapsedS, 1.0);
  EXPECT_DOUBLE_EQ(w.trailUntil({-8, 0}), -INFINITY);  // evicted: came back cleared
  EXPECT_DOUBLE_EQ(w.trailUntil({-7, 0}), 20.0);
  EXPECT_EQ(w.storedTiles(), 0u);
}

TEST(InteractionWindow, TrailsLeavingInOneFrameNeverShareASlot) {
  InteractionWindow w(withSlots(1));
  (void)w.update(1.0, 1.0, 0.0);
  hitTile(w, {-8, 0}, 0.0, 1.0);
  hitTile(w, {-8, 1}, 0.0, 1.0);
  hitTile(w, {-7, 0}, 0.0, 1.0);
  // Two trails leave together into one slot: the first (row-major) is kept, the other lost.
  const std::vector<TileTransfer> t = w.update(1.0 + kTileM, 1.0, 1.0);
  const std::vector<TileTransfer> saves = ofKind(t, Kind::Save);
  ASSERT_EQ(saves.size(), 1u);
  EXPECT_EQ(saves[0].key, (TileKey{-8, 0}));
  EXPECT_EQ(w.evictions(), 1u);
  // A later one evicts it.
  const std::vector<TileTransfer> later = ofKind(w.update(1.0 + 2 * kTileM, 1.0, 2.0), Kind::Save);
  ASSERT_EQ(later.size(), 1u);
  EXPECT_EQ(later[0].key, (TileKey{-7, 0}));
  EXPECT_EQ(later[0].storeSlot, 0u);
  EXPECT_EQ(w.evictions(), 2u);
  EXPECT_EQ(w.storedTiles(), 1u);
}

TEST(InteractionWindow, BudgetBelowOneTileKeepsNothing) {
  InteractionWindow w(withSlots(0, kTileBytes - 1));
  EXPECT_EQ(w.storeSlots(), 0u);
  (void)w.update(1.0, 1.0, 0.0);
  hitTile(w, {0, 0}, 0.0, 1.0);
  EXPECT_TRUE(ofKind(w.update(201.0, 1.0, 1.0), Kind::Save).empty());
  EXPECT_EQ(w.storedTiles(), 0u);
  EXPECT_EQ(w.storeBytesUsed(), 0u);
  EXPECT_EQ(w.evictions(), 1u);  // the trail was lost for lack of room
  EXPECT_TRUE(ofKind(w.update(1.0, 1.0, 2.0), Kind::Restore).empty());
}

TEST(InteractionWindow, EveryOneTileStepHandsTheLeavingWindowTilesToTheEnteringOnes) {
  InteractionWindow w(InteractionWindowOptions{});
  const double cx = -40.0, cy = -40.0;  // origin (−21, −21): all negative
  (void)w.update(cx, cy, 0.0);
  ASSERT_EQ(w.originTile(), (TileKey{-21, -21}));
  w.markHit(-1000.0, -1000.0, 1000.0, 1000.0, 0.0, 1.0);  // every window tile until 20 s
  double t = 0.0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      if (dx == 0 && dy == 0) continue;
      const size_t leaving = 256 - size_t(16 - std::abs(dx)) * size_t(16 - std::abs(dy));  // 16 or 31
      t += 0.5;
      const std::vector<TileTransfer> out = w.update(cx + dx * kTileM, cy + dy * kTileM, t);
      EXPECT_EQ(w.originTile(), (TileKey{-21 + dx, -21 + dy}));
      ASSERT_EQ(out.size(), 2 * leaving) << dx << " " << dy;
      const std::vector<TileTransfer> saves(out.begin(), out.begin() + std::ptrdiff_t(leaving));
      const std::vector<TileTransfer> clears(out.begin() + std::ptrdiff_t(leaving), out.end());
      EXPECT_EQ(ofKind(saves, Kind::Save).size(), leaving);
      EXPECT_EQ(ofKind(clears, Kind::Clear).size(), leaving);
      EXPECT_EQ(sortedWindowTiles(saves), sortedWindowTiles(clears));
      // Back: the entering tiles were clean, the saved ones all come back.
      t += 0.5;
      const std::vector<TileTransfer> back = w.update(cx, cy, t);
      ASSERT_EQ(back.size(), leaving);
      EXPECT_EQ(ofKind(back, Kind::Restore).size(), leaving);
      EXPECT_EQ(sortedWindowTiles(back), sortedWindowTiles(saves));
      for (const TileTransfer& r : back) EXPECT_DOUBLE_EQ(r.elapsedS, 0.5);
      EXPECT_EQ(w.storedTiles(), 0u);
    }
}

TEST(InteractionWindow, RandomWalkStaysInBudgetAndRestoresOnlyWhatASaveOfTheKeyFilled) {
  const uint64_t budget = 24 * kTileBytes + 1000;
  InteractionWindow w(withSlots(24, 1000));
  ASSERT_EQ(w.storeSlots(), 24u);
  std::mt19937_64 rng(19);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  struct Filled {
    TileKey key;
    double savedAtS;
  };
  std::map<uint32_t, Filled> slots;  // what the last Save put in each slot, until restored
  const std::vector<std::pair<double, double>> spots = {{0.0, 0.0}, {200.0, 0.0}, {-150.0, -170.0}};
  double x = 0.0, y = 0.0, t = 0.0;
  (void)w.update(x, y, t);
  uint64_t saves = 0, restores = 0;
  for (int step = 0; step < 10000; ++step) {
    t += 0.05 + 0.5 * u01(rng);
    if (u01(rng) < 0.02) {
      const auto& s = spots[size_t(u01(rng) * double(spots.size())) % spots.size()];
      x = s.first;
      y = s.second;
    } else {
      x += kTileM * std::floor(3.0 * u01(rng) - 1.0);
      y += kTileM * std::floor(3.0 * u01(rng) - 1.0);
    }
    const TileKey previous = w.originTile();
    const std::vector<TileTransfer> out = w.update(x, y, t);
    const TileKey origin = w.originTile();
    auto in = [](TileKey k, TileKey o) { return k.x >= o.x && k.x < o.x + 16 && k.y >= o.y && k.y < o.y + 16; };
    bool restoring = false;
    std::vector<uint32_t> savedNow;
    for (const TileTransfer& tr : out) {
      ASSERT_EQ(tr.windowTile, InteractionWindow::windowTileOf(tr.key, 16));
      if (tr.kind == Kind::Save) {
        ASSERT_FALSE(restoring) << "a Save after a Restore or Clear at step " << step;
        ASSERT_TRUE(in(tr.key, previous) && !in(tr.key, origin));
        ASSERT_LT(tr.storeSlot, w.storeSlots());
        ASSERT_EQ(std::count(savedNow.begin(), savedNow.end(), tr.storeSlot), 0) << "slot saved twice in a frame";
        savedNow.push_back(tr.storeSlot);
        slots[tr.storeSlot] = {tr.key, t};
        ++saves;
        continue;
      }
      restoring = true;
      ASSERT_TRUE(in(tr.key, origin) && !in(tr.key, previous));
      if (tr.kind != Kind::Restore) continue;
      const auto filled = slots.find(tr.storeSlot);
      ASSERT_NE(filled, slots.end()) << "Restore from a slot no Save filled, step " << step;
      ASSERT_EQ(filled->second.key, tr.key) << "step " << step;
      ASSERT_DOUBLE_EQ(tr.elapsedS, t - filled->second.savedAtS);
      ASSERT_GT(tr.elapsedS, 0.0);
      ASSERT_GT(w.trailUntil(tr.key), t);
      slots.erase(filled);
      ++restores;
    }
    ASSERT_LE(w.storeBytesUsed(), budget);
    ASSERT_LE(w.storedTiles(), w.storeSlots());
    // Random hits around the camera, up to 20 s of trail each.
    const int hits = int(4.0 * u01(rng));
    for (int h = 0; h < hits; ++h) {
      const double hx = x + 60.0 * (u01(rng) - 0.5), hy = y + 60.0 * (u01(rng) - 0.5);
      const double size = 4.0 * u01(rng);
      w.markHit(hx, hy, hx + size, hy + size, t, u01(rng));
    }
  }
  // The walk exercised the store: many saves and restores, and a full store (28 023 saves,
  // 16 805 restores, 10 166 evictions with libstdc++'s distributions).
  EXPECT_GT(saves, 20000u);
  EXPECT_GT(restores, 10000u);
  EXPECT_GT(w.evictions(), 5000u);
}

TEST(InteractionWindow, WindowTileOfNegativeKeysIsNonNegativeModulo) {
  EXPECT_EQ(InteractionWindow::windowTileOf({0, 0}, 16), 0u);
  EXPECT_EQ(InteractionWindow::windowTileOf({-1, -1}, 16), 255u);
  EXPECT_EQ(InteractionWindow::windowTileOf({-16, 0}, 16), 0u);
  EXPECT_EQ(InteractionWindow::windowTileOf({-17, -33}, 16), 15u + 16u * 15u);
  EXPECT_EQ(InteractionWindow::windowTileOf({17, -2}, 16), 1u + 16u * 14u);
  EXPECT_EQ(InteractionWindow::windowTileOf({-8, 5}, 16), 8u + 16u * 5u);
  EXPECT_EQ(
      InteractionWindow::windowTileOf({std::numeric_limits<int32_t>::min(), std::numeric_limits<int32_t>::max()}, 16),
      0u + 16u * 15u);
  EXPECT_EQ(InteractionWindow::windowTileOf({-1, -9}, 8), 7u + 8u * 7u);
  // A tile and the one a window's width further share their window tile.
  for (int k = -40; k <= 40; ++k)
    EXPECT_EQ(InteractionWindow::windowTileOf({k, k}, 16), InteractionWindow::windowTileOf({k + 16, k - 32}, 16));
}

}  // namespace
}  // namespace vegstream::simulation
