// Seed triangles of a lon/lat box by descent from the roots (seed_region.h; core seed
// ../shared/seeds/001_3eca9f2c7752e4fb.txt §3.1).

#include "terrain/seed_region.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "terrain/seed_triangles.h"

namespace vegstream::terrain {
namespace {

// The box in grid coordinates (gridZoom tile units; y southwards).
struct GridBox {
  double x0 = 0.0, y0 = 0.0, x1 = 0.0, y1 = 0.0;
};

GridBox gridBoxOf(const BintreeGrid& grid, const geo::GeoBounds& box) {
  const glm::dvec2 nw = geo::lonLatToTileXY({box.westDeg, box.northDeg}, grid.gridZoom());
  const glm::dvec2 se = geo::lonLatToTileXY({box.eastDeg, box.southDeg}, grid.gridZoom());
  return {nw.x, nw.y, se.x, se.y};
}

class Descent {
 public:
  Descent(const BintreeGrid& grid, const SeedRegionQuery& q) : grid_(grid), q_(q), box_(gridBoxOf(grid, q.box)) {}

  // Calls emit(path, corners) for every seed-level triangle of the box under root (x, y, tree).
  template <typename Emit>
  void run(const geo::TileRange& roots, Emit&& emit) const {
    for (int y = roots.minY; y <= roots.maxY; ++y)
      for (int x = roots.minX; x <= roots.maxX; ++x)
        for (uint8_t tree = 0; tree < 2; ++tree) {
          const TriPath p{x, y, tree, 0, 0};
          visit(p, grid_.rootCorners(x, y, tree), emit);
        }
  }

 private:
  template <typename Emit>
  void visit(const TriPath& p, const TriCorners& t, Emit& emit) const {
    const double minX = std::min({t.apex.x, t.left.x, t.right.x}), maxX = std::max({t.apex.x, t.left.x, t.right.x});
    const double minY = std::min({t.apex.y, t.left.y, t.right.y}), maxY = std::max({t.apex.y, t.left.y, t.right.y});
    // Overlap grows the triangle by one grid unit: a point on the flat (ENU) triangle maps back
    // to lon/lat a hair off the grid triangle (Mercator is not linear), never by a grid unit.
    const double g = q_.select == RegionSelect::Overlap ? 1.0 : 0.0;
    if (maxX + g < box_.x0 || minX - g >= box_.x1 || maxY + g < box_.y0 || minY - g >= box_.y1) return;
    if (p.level == q_.seedLevel) {
      if (q_.select == RegionSelect::Centroid) {
        // ×3 keeps the centroid exact (integer grid).
        const double cx = double(uint64_t{t.apex.x} + t.left.x + t.right.x);
        const double cy = double(uint64_t{t.apex.y} + t.left.y + t.right.y);
        if (cx < 3.0 * box_.x0 || cx >= 3.0 * box_.x1 || cy < 3.0 * box_.y0 || cy >= 3.0 * box_.y1) return;
      }
      emit(p, t);
      return;
    }
    visit(childPath(p, 0), child(t, 0), emit);
    visit(childPath(p, 1), child(t, 1), emit);
  }

  const BintreeGrid& grid_;
  const SeedRegionQuery& q_;
  GridBox box_;
};

}  // namespace

glm::dvec3 groundVertex(const BintreeGrid& grid, const geo::LocalFrame& frame, ResidentHeights& heights, GridPoint p) {
  // The same operations in the same order as RoamMesh::newVertex + applySample, so the result
  // is bit-identical to the mesh's vertex (RoamVertex::position(heightM)).
  const glm::dvec2 lonLat = geo::tileXYToLonLat(grid.tileXY(p, grid.gridZoom()), grid.gridZoom());
  const geo::Geodetic g{lonLat.y, lonLat.x, 0.0};
  const glm::dvec3 base = frame.toLocal(g);
  const glm::dvec3 up = frame.upAt(g, base);
  const double h = heights.sample(p).heightM;
  if (!(h == h)) return glm::dvec3(std::numeric_limits<double>::quiet_NaN());
  return base + up * h;
}

SeedRegion seedTrianglesIn(const BintreeGrid& grid, const geo::TileRange& roots, const geo::LocalFrame& frame,
                           ResidentHeights& heights, const SeedRegionQuery& query) {
  SeedRegion out;
  // Neighbouring triangles share vertices (up to 8 around a grid point): sample each once.
  std::unordered_map<uint64_t, glm::dvec3> vertices;
  auto vertexAt = [&](GridPoint p) {
    const uint64_t k = (uint64_t{p.x} << 32) | p.y;
    auto it = vertices.find(k);
    if (it == vertices.end()) it = vertices.emplace(k, groundVertex(grid, frame, heights, p)).first;
    return it->second;
  };
  Descent(grid, query).run(roots, [&](const TriPath& path, const TriCorners& t) {
    RegionSeedTriangle s;
    s.path = path;
    s.corners = t;
    s.key = seedKey(path);
    s.world = {vertexAt(t.apex), vertexAt(t.left), vertexAt(t.right)};
    for (const glm::dvec3& v : s.world) {
      if (!(v.x == v.x)) {
        ++out.nodataSkipped;
        return;
      }
    }
    s.plantCount = static_cast<float>(query.densityM2 * groundArea(s.world));
    out.triangles.push_back(s);
  });
  return out;
}

uint64_t countSeedTrianglesIn(const BintreeGrid& grid, const geo::TileRange& roots, const SeedRegionQuery& query) {
  uint64_t n = 0;
  Descent(grid, query).run(roots, [&](const TriPath&, const TriCorners&) { ++n; });
  return n;
}

}  // namespace vegstream::terrain
