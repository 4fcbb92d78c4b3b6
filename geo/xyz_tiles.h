#pragma once
// XYZ ("slippy map") tiles in the Web Mercator scheme used by OpenStreetMap, Mapbox terrain-RGB
// and AWS terrarium: zoom z splits the EPSG:3857 square (±85.0511° latitude) into 2^z × 2^z
// tiles, x counted from 180°W eastwards, y counted from the NORTH edge southwards (not TMS).
//
// Fractional tile coordinates ("tile xy"): tile (x, y) covers [x, x+1) × [y, y+1). Pixel
// coordinates within one tile: (0, 0) is the tile's north-west corner, the centre of pixel
// (i, j) is (i + 0.5, j + 0.5), and tileSize pixels span the tile. Longitude/latitude pairs
// are glm::dvec2 with x = longitude, y = latitude, degrees. Longitudes are not wrapped.

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "geo/bounds.h"

namespace vegstream::geo {

// 2^30 tiles a side is the most a signed int indexes; real data stops near z = 20.
inline constexpr int kMaxTileZoom = 30;
inline constexpr int kDefaultTileSize = 256;

struct TileId {
  int z = 0;
  int x = 0;
  int y = 0;

  // Ordered by z, then x, then y (std::map, sorted listings).
  auto operator<=>(const TileId&) const = default;
};

// 0 ≤ z ≤ kMaxTileZoom and 0 ≤ x, y < 2^z.
bool isValid(const TileId& t);
// "12/758/1608" — the same order as the {z}/{x}/{y} path templates.
std::string toString(const TileId& t);

// 2^z as a double (no overflow up to kMaxTileZoom).
double tilesPerSide(int z);

// Latitudes beyond ±kWebMercatorMaxLatDeg are clamped to the edge of the pyramid (the poles map
// to the top / bottom edge), as every slippy map does.
glm::dvec2 lonLatToTileXY(glm::dvec2 lonLat, int z);
glm::dvec2 tileXYToLonLat(glm::dvec2 tileXY, int z);
// EPSG:3857 metres ↔ fractional tile coordinates (exact affine map, no trigonometry).
glm::dvec2 mercatorToTileXY(glm::dvec2 mercatorM, int z);
glm::dvec2 tileXYToMercator(glm::dvec2 tileXY, int z);

// The tile that contains the point (clamped into the grid, so ±180° and the edges belong to a
// tile).
TileId tileContaining(glm::dvec2 lonLat, int z);

GeoBounds tileBoundsLonLat(const TileId& t);
ProjectedBounds tileBoundsMercator(const TileId& t);

glm::dvec2 pixelToLonLat(const TileId& t, glm::dvec2 pixel, int tileSize = kDefaultTileSize);
glm::dvec2 lonLatToPixel(const TileId& t, glm::dvec2 lonLat, int tileSize = kDefaultTileSize);
glm::dvec2 pixelToMercator(const TileId& t, glm::dvec2 pixel, int tileSize = kDefaultTileSize);
glm::dvec2 mercatorToPixel(const TileId& t, glm::dvec2 mercatorM, int tileSize = kDefaultTileSize);

// Inclusive range of tiles at one zoom.
struct TileRange {
  int z = 0;
  int minX = 0;
  int minY = 0;
  int maxX = -1;
  int maxY = -1;

  std::int64_t count() const {
    return maxX < minX || maxY < minY ? 0 : std::int64_t{maxX - minX + 1} * std::int64_t{maxY - minY + 1};
  }
  bool contains(const TileId& t) const { return t.z == z && t.x >= minX && t.x <= maxX && t.y >= minY && t.y <= maxY; }
};

// The tiles whose area overlaps the box's area: an edge that lies exactly on a tile boundary
// does not pull in the neighbour; a box of zero width or height still yields the tile(s)
// holding it. One range, or two when the box crosses the antimeridian (west part first).
std::vector<TileRange> tileRangesCovering(const GeoBounds& box, int z);
// The same tiles listed row by row (north first). Callers bound z: a continent at z 18 is
// billions of tiles — count with tileRangesCovering first.
std::vector<TileId> tilesCovering(const GeoBounds& box, int z);

TileId parent(const TileId& t);                   // t.z > 0 (asserted)
std::array<TileId, 4> children(const TileId& t);  // NW, NE, SW, SE; t.z < kMaxTileZoom (asserted)

// EPSG:3857 metres per pixel at zoom z (the same everywhere in projected units).
double mercatorResolution(int z, int tileSize = kDefaultTileSize);
// True metres on the WGS 84 ellipsoid per pixel, east-west, at a latitude:
// mercatorResolution · cos φ / sqrt(1 − e² sin² φ). (Bing's spherical cos φ form is up to 0.34 %
// coarser; north-south the scale differs slightly as EPSG:3857 is not conformal on the ellipsoid.)
double groundResolution(double latDeg, int z, int tileSize = kDefaultTileSize);
// The fractional zoom whose groundResolution at latDeg equals metresPerPixel (> 0, asserted).
// An importer takes ceil() of it so that no source detail is lost.
double zoomForResolution(double metresPerPixel, double latDeg, int tileSize = kDefaultTileSize);

}  // namespace vegstream::geo

template <>
struct std::hash<vegstream::geo::TileId> {
  std::size_t operator()(const vegstream::geo::TileId& t) const noexcept {
    // x, y < 2^30 pack into 60 bits; z is folded in through a golden-ratio multiplier, and
    // splitmix64's finaliser then spreads neighbouring tiles across buckets.
    std::uint64_t k = ((std::uint64_t(std::uint32_t(t.x)) << 30) | std::uint64_t(std::uint32_t(t.y))) ^
                      (std::uint64_t(std::uint32_t(t.z)) * 0x9e3779b97f4a7c15ULL);
    k ^= k >> 30;
    k *= 0xbf58476d1ce4e5b9ULL;
    k ^= k >> 27;
    k *= 0x94d049bb133111ebULL;
    k ^= k >> 31;
    return static_cast<std::size_t>(k);
  }
};
