#pragma once
// Geometry and identity of the triangles of a ROAM binary triangle tree (Duchaineau et al. 1997;
// seed 001_3eca9f2c7752e4fb.txt §3.1 and fig. 4) laid over the XYZ Web Mercator pyramid.
//
// Every root tile (zoom `rootZoom`, the dataset's coarsest) is a square split along its NW–SE
// diagonal into two right isosceles triangles, the roots of two bintrees. A triangle is
// (apex, left, right): the right angle at the apex, the base (hypotenuse) from left to right,
// counter-clockwise seen from above (east = +x, north = +y). Splitting along the base gives
//     child 0 = (m, apex, left)      child 1 = (m, right, apex)      m = (left + right) / 2,
// both again counter-clockwise. Two levels down a triangle is half of a square one zoom finer,
// so a triangle of level L lies inside one tile of zoom rootZoom + ⌊L/2⌋ (its *square*); the
// squares' diagonals alternate (a 4-8 mesh): a square of zoom z > rootZoom is split along its
// NW–SE diagonal when x + y is even and along its SW–NE diagonal when it is odd.
//
// Vertices live on an integer grid: the pixel corners of the dataset's finest tiles, subdivided
// `extraLevels` / 2 more times (zoom `gridZoom` = maxZoom + 8 + extraLevels / 2 for 256-pixel
// tiles), x eastwards and y southwards as in XYZ tiles. Every vertex down to maxLevel() is
// exactly on that grid, so midpoints are exact integer halves. The extra levels go below the
// data's pixels (on its bilinear surface): seed triangles can be smaller than a pixel.
//
// A triangle's identity (TriPath) is its root and the child indices on the way down: the same
// piece of ground is the same path from any viewpoint, in every session.

#include <array>
#include <cassert>
#include <cstdint>

#include <glm/vec2.hpp>

#include "geo/xyz_tiles.h"

namespace vegstream::terrain {

// Levels of a tile's own bintree down to its pixels: a level-16 triangle is half a pixel square.
inline constexpr int kTileLevels = 16;
static_assert((1 << (kTileLevels / 2)) == geo::kDefaultTileSize);

struct GridPoint {
  uint32_t x = 0, y = 0;
  auto operator<=>(const GridPoint&) const = default;
};

inline GridPoint midpoint(GridPoint a, GridPoint b) {
  assert(((a.x + b.x) & 1u) == 0 && ((a.y + b.y) & 1u) == 0);  // exact: the level is not too deep
  return {(a.x + b.x) / 2, (a.y + b.y) / 2};
}

struct TriCorners {
  GridPoint apex, left, right;
  bool operator==(const TriCorners&) const = default;
};

inline TriCorners child(const TriCorners& t, int which) {
  const GridPoint m = midpoint(t.left, t.right);
  return which == 0 ? TriCorners{m, t.apex, t.left} : TriCorners{m, t.right, t.apex};
}

struct TriPath {
  int32_t rootX = 0, rootY = 0;  // the root tile at the grid's root zoom
  uint8_t tree = 0;              // 0: the south-west half of the root tile, 1: the north-east half
  uint8_t level = 0;             // splits below the root
  uint64_t bits = 0;             // child indices, the first split in the most significant bit used
  auto operator<=>(const TriPath&) const = default;
};

inline TriPath childPath(const TriPath& p, int which) {
  assert(p.level < 63);
  TriPath c = p;
  c.level = static_cast<uint8_t>(p.level + 1);
  c.bits = (p.bits << 1) | static_cast<uint64_t>(which);
  return c;
}

// The integer grid of one dataset's bintree.
class BintreeGrid {
 public:
  BintreeGrid() = default;
  BintreeGrid(int rootZoom, int maxZoom, int extraLevels = 0)
      : rootZoom_(rootZoom), maxZoom_(maxZoom), extraLevels_(extraLevels) {
    assert(rootZoom >= 0 && rootZoom <= maxZoom && extraLevels >= 0 && gridZoom() <= 31);
  }
  int rootZoom() const { return rootZoom_; }
  int maxZoom() const { return maxZoom_; }
  int gridZoom() const { return maxZoom_ + kTileLevels / 2 + (extraLevels_ + 1) / 2; }
  // The level of half a pixel square of the finest tiles.
  int pixelLevel() const { return 2 * (maxZoom_ - rootZoom_) + kTileLevels; }
  // The deepest level a triangle may have.
  int maxLevel() const { return pixelLevel() + extraLevels_; }

  // Corners of a root triangle.
  TriCorners rootCorners(int32_t rootX, int32_t rootY, int tree) const {
    const uint32_t s = 1u << (gridZoom() - rootZoom_);
    const uint32_t x0 = static_cast<uint32_t>(rootX) * s, y0 = static_cast<uint32_t>(rootY) * s;
    const GridPoint nw{x0, y0}, ne{x0 + s, y0}, se{x0 + s, y0 + s}, sw{x0, y0 + s};
    return tree == 0 ? TriCorners{sw, se, nw} : TriCorners{ne, nw, se};
  }
  TriCorners corners(const TriPath& p) const {
    TriCorners t = rootCorners(p.rootX, p.rootY, p.tree);
    for (int i = p.level - 1; i >= 0; --i) t = child(t, static_cast<int>((p.bits >> i) & 1u));
    return t;
  }

  // Fractional tile coordinates of a grid point at zoom z.
  glm::dvec2 tileXY(GridPoint p, int z) const {
    const double scale = 1.0 / static_cast<double>(uint64_t{1} << (gridZoom() - z));
    return {static_cast<double>(p.x) * scale, static_cast<double>(p.y) * scale};
  }
  // Zoom of the square a triangle of `level` lies in.
  int squareZoom(int level) const { return rootZoom_ + level / 2; }
  // The square (tile) a triangle lies in: the tile of its squareZoom containing its centroid.
  geo::TileId square(const TriCorners& t, int level) const {
    const int z = squareZoom(level);
    const int shift = gridZoom() - z;
    // The centroid, ×3 to stay integer.
    const uint64_t cx = uint64_t{t.apex.x} + t.left.x + t.right.x, cy = uint64_t{t.apex.y} + t.left.y + t.right.y;
    return {z, static_cast<int>(cx / (3ull << shift)), static_cast<int>(cy / (3ull << shift))};
  }

  // Diagonal of a square in this grid's bintree: false NW–SE, true SW–NE (see the top).
  bool diagonalIsSwNe(const geo::TileId& square) const {
    return square.z > rootZoom_ && ((square.x + square.y) & 1) != 0;
  }

 private:
  int rootZoom_ = 0;
  int maxZoom_ = 0;
  int extraLevels_ = 0;
};

}  // namespace vegstream::terrain
