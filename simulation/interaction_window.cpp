// The interaction field's window and trail store bookkeeping (see the header).
#include "simulation/interaction_window.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <optional>

namespace vegstream::simulation {
namespace {

constexpr double kNoTrail = -std::numeric_limits<double>::infinity();

uint32_t slotsFor(const InteractionWindowOptions& o) {
  assert(o.tileBytes > 0);
  return static_cast<uint32_t>(std::min<uint64_t>(o.storeBytes / o.tileBytes, std::numeric_limits<uint32_t>::max()));
}

}  // namespace

InteractionWindow::InteractionWindow(const InteractionWindowOptions& options)
    : options_(options), store_(slotsFor(options)) {
  assert(options.windowTiles > 0 && options.tileM > 0.0 && options.recoveryPerS > 0.0);
  const auto n = static_cast<std::size_t>(options.windowTiles);
  trailUntil_.assign(n * n, kNoTrail);
}

uint32_t InteractionWindow::windowTileOf(TileKey key, int windowTiles) {
  assert(windowTiles > 0);
  // C++'s % keeps the dividend's sign: shift the remainder into [0, n).
  const int x = (key.x % windowTiles + windowTiles) % windowTiles;
  const int y = (key.y % windowTiles + windowTiles) % windowTiles;
  return static_cast<uint32_t>(x + windowTiles * y);
}

TileKey InteractionWindow::tileAt(double x, double y) const {
  const double fx = std::floor(x / options_.tileM), fy = std::floor(y / options_.tileM);
  // Room for the window around it without overflowing int32 (±6.8 million km at 3.2 m).
  [[maybe_unused]] constexpr double kLimit = double(std::numeric_limits<int32_t>::max() / 2);
  assert(std::abs(fx) < kLimit && std::abs(fy) < kLimit && "camera outside the local frame");
  return {static_cast<int32_t>(fx), static_cast<int32_t>(fy)};
}

bool InteractionWindow::inWindow(TileKey key, TileKey origin) const {
  const int64_t dx = int64_t{key.x} - origin.x, dy = int64_t{key.y} - origin.y;
  return dx >= 0 && dy >= 0 && dx < options_.windowTiles && dy < options_.windowTiles;
}

double InteractionWindow::trailUntil(TileKey key) const {
  if (!started_ || !inWindow(key, origin_)) return kNoTrail;
  return trailUntil_[windowTileOf(key, options_.windowTiles)];
}

std::vector<TileTransfer> InteractionWindow::update(double cameraX, double cameraY, double timeS) {
  assert((!started_ || timeS >= nowS_) && "time runs forwards");
  const int n = options_.windowTiles;
  const TileKey centre = tileAt(cameraX, cameraY);
  const TileKey origin{centre.x - n / 2, centre.y - n / 2};
  const TileKey previous = origin_;
  const bool first = !started_;
  started_ = true;
  origin_ = origin;
  nowS_ = timeS;
  std::vector<TileTransfer> out;
  if (first) {
    // The field's memory is undefined until written: clear it all.
    out.reserve(trailUntil_.size());
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const TileKey k{origin.x + x, origin.y + y};
        out.push_back({TileTransfer::Kind::Clear, windowTileOf(k, n), 0, 0.0, k});
      }
    return out;
  }
  store_.dropRecovered(timeS);
  if (origin == previous) return out;

  // The entering tiles, with what the store holds of them. They are taken out before any save,
  // so that no save evicts a tile that re-enters now; their slots stay out of the pool until the
  // saves are planned, so that no save (ordered before the restores) overwrites them.
  struct Entering {
    TileKey key;
    std::optional<TrailStore::Entry> stored;
  };
  std::vector<Entering> entering;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const TileKey k{origin.x + x, origin.y + y};
      if (!inWindow(k, previous)) entering.push_back({k, store_.take(k)});
    }

  // Saves: the leaving tiles still holding a trail. Their trailUntil_ entries are read before
  // the entering tiles take the window tiles over.
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const TileKey k{previous.x + x, previous.y + y};
      if (inWindow(k, origin)) continue;
      const uint32_t w = windowTileOf(k, n);
      if (!(trailUntil_[w] > timeS)) continue;
      if (const std::optional<uint32_t> slot = store_.save(k, timeS, trailUntil_[w]))
        out.push_back({TileTransfer::Kind::Save, w, *slot, 0.0, k});
    }

  // Restores and Clears, in the entering tiles' order.
  for (const Entering& e : entering) {
    const uint32_t w = windowTileOf(e.key, n);
    if (e.stored && e.stored->recoveredAtS > timeS) {
      out.push_back({TileTransfer::Kind::Restore, w, e.stored->slot, timeS - e.stored->savedAtS, e.key});
      trailUntil_[w] = e.stored->recoveredAtS;
    } else {
      out.push_back({TileTransfer::Kind::Clear, w, 0, 0.0, e.key});
      trailUntil_[w] = kNoTrail;
    }
    if (e.stored) store_.release(e.stored->slot);
  }
  return out;
}

void InteractionWindow::markHit(double minX, double minY, double maxX, double maxY, double timeS, double strength) {
  assert(started_ && "the window has no place before the first update");
  assert(minX <= maxX && minY <= maxY && strength >= 0.0);
  const double until = timeS + strength / options_.recoveryPerS;
  const double t = options_.tileM;
  const int n = options_.windowTiles;
  // The box's tiles clamped to the window in doubles first: a box may reach far beyond it.
  const double x0 = std::max(std::floor(minX / t), double(origin_.x));
  const double x1 = std::min(std::floor(maxX / t), double(origin_.x) + (n - 1));
  const double y0 = std::max(std::floor(minY / t), double(origin_.y));
  const double y1 = std::min(std::floor(maxY / t), double(origin_.y) + (n - 1));
  if (!(x0 <= x1 && y0 <= y1)) return;
  for (auto y = static_cast<int32_t>(y0); y <= static_cast<int32_t>(y1); ++y)
    for (auto x = static_cast<int32_t>(x0); x <= static_cast<int32_t>(x1); ++x) {
      double& w = trailUntil_[windowTileOf({x, y}, n)];
      w = std::max(w, until);
    }
}

}  // namespace vegstream::simulation
