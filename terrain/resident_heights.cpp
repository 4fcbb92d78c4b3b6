// Heights, slopes and wedgie thicknesses over the resident height tiles (resident_heights.h).

#include "terrain/resident_heights.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "terrain/wedgie_table.h"

namespace vegstream::terrain {
namespace {

constexpr double kEarthCircumferenceM = 40075016.685578488;

uint64_t packTile(const geo::TileId& t) {
  return (uint64_t(t.z) << 58) | (uint64_t(uint32_t(t.x)) << 29) | uint64_t(uint32_t(t.y));
}

geo::TileId clampedTile(glm::dvec2 xy, int z) {
  const int n = 1 << z;
  return {z, std::clamp(static_cast<int>(std::floor(xy.x)), 0, n - 1),
          std::clamp(static_cast<int>(std::floor(xy.y)), 0, n - 1)};
}

}  // namespace

double sampleHeight(const datasets::HeightTile& tile, int z, double tileX, double tileY) {
  assert(tile.size > 0 && tile.heights.size() == static_cast<size_t>(tile.size) * static_cast<size_t>(tile.size));
  assert(tile.id.z <= z);
  // Into the tile's pixel space: zoom z tile coordinates shrink by 2 per level up.
  const double scale = std::ldexp(1.0, tile.id.z - z);
  const double n = static_cast<double>(tile.size);
  const double gx = std::clamp((tileX * scale - tile.id.x) * n - 0.5, 0.0, n - 1.0);
  const double gy = std::clamp((tileY * scale - tile.id.y) * n - 0.5, 0.0, n - 1.0);
  const int x0 = static_cast<int>(gx), y0 = static_cast<int>(gy);
  const double fx = gx - x0, fy = gy - y0;
  const int x1 = std::min(x0 + 1, tile.size - 1), y1 = std::min(y0 + 1, tile.size - 1);
  // A neighbour with zero weight is not read, so a sample exactly on a pixel centre next to
  // nodata is still valid; any other nodata neighbour makes the result NaN.
  auto row = [&](int y) {
    const double a = static_cast<double>(tile.at(x0, y));
    return fx == 0.0 ? a : a * (1.0 - fx) + static_cast<double>(tile.at(x1, y)) * fx;
  };
  const double top = row(y0);
  return fy == 0.0 ? top : top * (1.0 - fy) + row(y1) * fy;
}

ResidentHeights::ResidentHeights(BintreeGrid grid, Find find) : grid_(grid), find_(std::move(find)) {}

const streaming::ResidentTile* ResidentHeights::find(const geo::TileId& tile) {
  const uint64_t key = packTile(tile);
  auto it = cache_.find(key);
  if (it != cache_.end()) return it->second;
  const streaming::ResidentTile* t = find_(tile);
  if (t && !t->heights) t = nullptr;
  cache_.emplace(key, t);
  return t;
}

double ResidentHeights::bilinearAcross(const datasets::HeightTile& tile, int z, glm::dvec2 xy) {
  // Bilinear in the global pixel grid of the tile's zoom: pixels beyond the tile's edge come
  // from its neighbour at the same zoom when that is resident (so heights are continuous across
  // tile borders), else the edge is clamped.
  const int zt = tile.id.z;
  const double n = static_cast<double>(tile.size);
  const double scale = std::ldexp(1.0, zt - z);
  const double gx = xy.x * scale * n - 0.5, gy = xy.y * scale * n - 0.5;
  const double fx0 = std::floor(gx), fy0 = std::floor(gy);
  const double fx = gx - fx0, fy = gy - fy0;
  const long long x0 = static_cast<long long>(fx0), y0 = static_cast<long long>(fy0);
  const long long tileX0 = (long long)tile.id.x * tile.size, tileY0 = (long long)tile.id.y * tile.size;
  const long long side = (long long)tile.size << zt;
  auto pixel = [&](long long px, long long py) -> double {
    px = std::clamp(px, 0ll, side - 1);
    py = std::clamp(py, 0ll, side - 1);
    const long long lx = px - tileX0, ly = py - tileY0;
    if (lx >= 0 && ly >= 0 && lx < tile.size && ly < tile.size) return tile.at(int(lx), int(ly));
    const geo::TileId other{zt, int(px / tile.size), int(py / tile.size)};
    const streaming::ResidentTile* r = find(other);
    if (r && r->heights->id == other) return r->heights->at(int(px % tile.size), int(py % tile.size));
    return tile.at(int(std::clamp(lx, 0ll, (long long)tile.size - 1)),
                   int(std::clamp(ly, 0ll, (long long)tile.size - 1)));
  };
  // A neighbour with zero weight is not read (a sample on a pixel centre next to nodata is valid).
  auto row = [&](long long y) {
    const double a = pixel(x0, y);
    return fx == 0.0 ? a : a * (1.0 - fx) + pixel(x0 + 1, y) * fx;
  };
  const double top = row(y0);
  return fy == 0.0 ? top : top * (1.0 - fy) + row(y0 + 1) * fy;
}

HeightSample ResidentHeights::sampleTileXY(glm::dvec2 xy, int z) {
  HeightSample s;
  const streaming::ResidentTile* r = find(clampedTile(xy, z));
  if (!r) return s;
  const datasets::HeightTile& tile = *r->heights;
  s.sourceZoom = tile.id.z;
  s.heightM = bilinearAcross(tile, z, xy);
  if (std::isnan(s.heightM)) return s;
  // Central differences one source pixel apart (one-sided where a neighbour is nodata).
  const double d = std::ldexp(1.0, z - tile.id.z) / tile.size;  // one source pixel in zoom-z tile units
  const double latDeg = geo::tileXYToLonLat(xy, z).y;
  const double pixelM =
      kEarthCircumferenceM / (geo::tilesPerSide(tile.id.z) * tile.size) * std::cos(latDeg * M_PI / 180.0);
  auto diff = [&](glm::dvec2 step) {
    const double a = bilinearAcross(tile, z, xy + step);
    const double b = bilinearAcross(tile, z, xy - step);
    if (!std::isnan(a) && !std::isnan(b)) return (a - b) / (2.0 * pixelM);
    if (!std::isnan(a)) return (a - s.heightM) / pixelM;
    if (!std::isnan(b)) return (s.heightM - b) / pixelM;
    return 0.0;
  };
  s.slope = {diff({d, 0.0}), -diff({0.0, d})};  // tile y grows southwards
  return s;
}

double ResidentHeights::heightTileXY(glm::dvec2 xy, int z) {
  const streaming::ResidentTile* r = find(clampedTile(xy, z));
  return r ? bilinearAcross(*r->heights, z, xy) : std::numeric_limits<double>::quiet_NaN();
}

HeightSample ResidentHeights::sample(GridPoint p) {
  return sampleTileXY(grid_.tileXY(p, grid_.maxZoom()), grid_.maxZoom());
}

HeightSample ResidentHeights::sampleLonLat(double latDeg, double lonDeg) {
  return sampleTileXY(geo::lonLatToTileXY({lonDeg, latDeg}, grid_.maxZoom()), grid_.maxZoom());
}

float ResidentHeights::thickness(const TriCorners& t, int level) {
  geo::TileId square = grid_.square(t, level);
  if (square.z > grid_.maxZoom()) {
    const int k = square.z - grid_.maxZoom();
    square = {grid_.maxZoom(), square.x >> k, square.y >> k};
  }
  const streaming::ResidentTile* r = find(square);
  const auto* table = r ? dynamic_cast<const WedgieTable*>(r->extra.get()) : nullptr;
  if (!table) return std::numeric_limits<float>::quiet_NaN();
  const geo::TileId& id = table->tile();
  const int localLevel = level - 2 * (id.z - grid_.rootZoom());
  assert(localLevel >= 0);
  auto local = [&](GridPoint p) {  // pixel-corner coordinates in the tile (exact to kTileLevels)
    const int shift = grid_.gridZoom() - (id.z + kTileLevels / 2);
    return GridPoint{(p.x >> shift) - uint32_t(id.x) * geo::kDefaultTileSize,
                     (p.y >> shift) - uint32_t(id.y) * geo::kDefaultTileSize};
  };
  if (localLevel <= kStoredLevels) {
    const glm::dvec2 a = grid_.tileXY(t.apex, id.z), l = grid_.tileXY(t.left, id.z), rr = grid_.tileXY(t.right, id.z);
    const glm::dvec2 centroidPx = ((a + l + rr) / 3.0 - glm::dvec2(id.x, id.y)) * double(geo::kDefaultTileSize);
    return table->thickness(localLevel, centroidPx);
  }
  if (localLevel <= kTileLevels)
    return table->deepThickness(*r->heights, {local(t.apex), local(t.left), local(t.right)}, localLevel);
  // Inside one pixel the surface is bilinear: its departure from a triangle's plane shrinks by
  // half per level, so the nested sum is twice the departure at the base midpoint.
  const double hm = heightTileXY(0.5 * (grid_.tileXY(t.left, id.z) + grid_.tileXY(t.right, id.z)), id.z);
  const double hl = heightTileXY(grid_.tileXY(t.left, id.z), id.z);
  const double hr = heightTileXY(grid_.tileXY(t.right, id.z), id.z);
  if (std::isnan(hm) || std::isnan(hl) || std::isnan(hr)) return kNoData;
  return static_cast<float>(2.0 * std::abs(hm - 0.5 * (hl + hr)));
}

ResidentHeights::Find findResidentHeights(streaming::TileStreamer& streamer) {
  return [&streamer](const geo::TileId& tile) -> const streaming::ResidentTile* {
    return streamer.findResident({streaming::TileLayer::Height, tile}).tile.get();
  };
}

}  // namespace vegstream::terrain
