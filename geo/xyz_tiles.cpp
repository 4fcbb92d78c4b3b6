#include "geo/xyz_tiles.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

#include <GeographicLib/Constants.hpp>

#include "geo/projection.h"

namespace vegstream::geo {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// π·a: EPSG:3857 spans [-halfWorld, halfWorld] in both axes.
double halfWorld() { return std::numbers::pi * GeographicLib::Constants::WGS84_a(); }

// Tile coordinates of box edges computed through trigonometry land a few ulps off the integer
// they mean (a tile's own bounds fed back in); snap them so that an edge on a tile boundary
// does not pull in the neighbour. 1e-9 tile is 40 µm even at zoom 0.
double snap(double t) {
  const double r = std::round(t);
  return std::abs(t - r) < 1e-9 ? r : t;
}

TileRange rangeFor(double west, double south, double east, double north, int z) {
  const glm::dvec2 nw = lonLatToTileXY({west, north}, z);
  const glm::dvec2 se = lonLatToTileXY({east, south}, z);
  const int last = static_cast<int>(tilesPerSide(z)) - 1;
  const auto first = [last](double t) { return std::clamp(static_cast<int>(std::floor(snap(t))), 0, last); };
  // Last tile whose interior the edge reaches: ceil − 1, but never before the first tile (a
  // degenerate box still lies in one tile).
  const auto lastOf = [last](double t, int lo) {
    return std::clamp(std::max(static_cast<int>(std::ceil(snap(t))) - 1, lo), 0, last);
  };
  TileRange r;
  r.z = z;
  r.minX = first(nw.x);
  r.minY = first(nw.y);
  r.maxX = lastOf(se.x, r.minX);
  r.maxY = lastOf(se.y, r.minY);
  return r;
}

}  // namespace

bool isValid(const TileId& t) {
  if (t.z < 0 || t.z > kMaxTileZoom) return false;
  const std::int64_t n = std::int64_t{1} << t.z;
  return t.x >= 0 && t.y >= 0 && t.x < n && t.y < n;
}

std::string toString(const TileId& t) {
  return std::to_string(t.z) + "/" + std::to_string(t.x) + "/" + std::to_string(t.y);
}

double tilesPerSide(int z) {
  assert(z >= 0 && z <= kMaxTileZoom);
  return std::ldexp(1.0, z);
}

glm::dvec2 mercatorToTileXY(glm::dvec2 m, int z) {
  const double h = halfWorld();
  const double n = tilesPerSide(z);
  return {(m.x + h) / (2.0 * h) * n, (h - m.y) / (2.0 * h) * n};
}

glm::dvec2 tileXYToMercator(glm::dvec2 t, int z) {
  const double h = halfWorld();
  const double n = tilesPerSide(z);
  return {t.x / n * 2.0 * h - h, h - t.y / n * 2.0 * h};
}

glm::dvec2 lonLatToTileXY(glm::dvec2 lonLat, int z) {
  const double lat = std::clamp(lonLat.y, -kWebMercatorMaxLatDeg, kWebMercatorMaxLatDeg);
  return mercatorToTileXY(lonLatToWebMercator({lonLat.x, lat}), z);
}

glm::dvec2 tileXYToLonLat(glm::dvec2 tileXY, int z) { return webMercatorToLonLat(tileXYToMercator(tileXY, z)); }

TileId tileContaining(glm::dvec2 lonLat, int z) {
  const glm::dvec2 t = lonLatToTileXY(lonLat, z);
  const int last = static_cast<int>(tilesPerSide(z)) - 1;
  return TileId{z, std::clamp(static_cast<int>(std::floor(t.x)), 0, last),
                std::clamp(static_cast<int>(std::floor(t.y)), 0, last)};
}

GeoBounds tileBoundsLonLat(const TileId& t) {
  assert(isValid(t));
  const glm::dvec2 nw = tileXYToLonLat(glm::dvec2(t.x, t.y), t.z);
  const glm::dvec2 se = tileXYToLonLat(glm::dvec2(t.x + 1, t.y + 1), t.z);
  return GeoBounds{nw.x, se.y, se.x, nw.y};
}

ProjectedBounds tileBoundsMercator(const TileId& t) {
  assert(isValid(t));
  const glm::dvec2 nw = tileXYToMercator(glm::dvec2(t.x, t.y), t.z);
  const glm::dvec2 se = tileXYToMercator(glm::dvec2(t.x + 1, t.y + 1), t.z);
  return ProjectedBounds{{nw.x, se.y}, {se.x, nw.y}};
}

glm::dvec2 pixelToMercator(const TileId& t, glm::dvec2 pixel, int tileSize) {
  assert(tileSize > 0);
  return tileXYToMercator(glm::dvec2(t.x, t.y) + pixel / static_cast<double>(tileSize), t.z);
}

glm::dvec2 mercatorToPixel(const TileId& t, glm::dvec2 mercatorM, int tileSize) {
  assert(tileSize > 0);
  return (mercatorToTileXY(mercatorM, t.z) - glm::dvec2(t.x, t.y)) * static_cast<double>(tileSize);
}

glm::dvec2 pixelToLonLat(const TileId& t, glm::dvec2 pixel, int tileSize) {
  return webMercatorToLonLat(pixelToMercator(t, pixel, tileSize));
}

glm::dvec2 lonLatToPixel(const TileId& t, glm::dvec2 lonLat, int tileSize) {
  assert(tileSize > 0);
  return (lonLatToTileXY(lonLat, t.z) - glm::dvec2(t.x, t.y)) * static_cast<double>(tileSize);
}

std::vector<TileRange> tileRangesCovering(const GeoBounds& box, int z) {
  assert(z >= 0 && z <= kMaxTileZoom);
  assert(box.southDeg <= box.northDeg);
  if (!box.crossesAntimeridian()) return {rangeFor(box.westDeg, box.southDeg, box.eastDeg, box.northDeg, z)};
  return {rangeFor(box.westDeg, box.southDeg, 180.0, box.northDeg, z),
          rangeFor(-180.0, box.southDeg, box.eastDeg, box.northDeg, z)};
}

std::vector<TileId> tilesCovering(const GeoBounds& box, int z) {
  const std::vector<TileRange> ranges = tileRangesCovering(box, z);
  std::int64_t total = 0;
  for (const TileRange& r : ranges) total += r.count();
  std::vector<TileId> tiles;
  tiles.reserve(static_cast<std::size_t>(total));
  for (const TileRange& r : ranges) {
    for (int y = r.minY; y <= r.maxY; ++y) {
      for (int x = r.minX; x <= r.maxX; ++x) tiles.push_back(TileId{z, x, y});
    }
  }
  return tiles;
}

TileId parent(const TileId& t) {
  assert(isValid(t) && t.z > 0);
  return TileId{t.z - 1, t.x / 2, t.y / 2};
}

std::array<TileId, 4> children(const TileId& t) {
  assert(isValid(t) && t.z < kMaxTileZoom);
  const int z = t.z + 1;
  const int x = 2 * t.x;
  const int y = 2 * t.y;
  return {TileId{z, x, y}, TileId{z, x + 1, y}, TileId{z, x, y + 1}, TileId{z, x + 1, y + 1}};
}

double mercatorResolution(int z, int tileSize) {
  assert(tileSize > 0);
  return 2.0 * halfWorld() / (static_cast<double>(tileSize) * tilesPerSide(z));
}

double groundResolution(double latDeg, int z, int tileSize) {
  // East-west, a degree of longitude is N·cos φ on the ellipsoid (N the prime-vertical radius
  // a / sqrt(1 − e² sin² φ)) and a·(π/180) in EPSG:3857.
  const double f = GeographicLib::Constants::WGS84_f();
  const double e2 = f * (2.0 - f);
  const double s = std::sin(latDeg * kDeg);
  return mercatorResolution(z, tileSize) * std::cos(latDeg * kDeg) / std::sqrt(1.0 - e2 * s * s);
}

double zoomForResolution(double metresPerPixel, double latDeg, int tileSize) {
  assert(metresPerPixel > 0.0);
  return std::log2(groundResolution(latDeg, 0, tileSize) / metresPerPixel);
}

}  // namespace vegstream::geo
