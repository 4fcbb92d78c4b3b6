#pragma once
// Every seed triangle of a lon/lat box, without a camera: the ground plants grow on, for tools
// that want all plants of an area at full density (`vegstream plants`) and for tests.
// Core seed ../shared/seeds/001_3eca9f2c7752e4fb.txt §3.1 (seed triangles are the bintree's
// triangles of one fixed level) and §2.2 (a plant depends only on its triangle and its index).
//
// Why this gives the same plants as a flight: a seed triangle's identity is its TriPath and its
// vertices are the grid points of that path placed exactly as RoamMesh places them (the point on
// the ellipsoid, frame.toLocal({lat, lon, 0}), moved along the ellipsoid normal frame.upAt(…) by
// the height ResidentHeights samples there). ROAM's seed triangles that are not `interpolated`
// are the same paths with the same vertices — bit for bit, for the same resident heights —
// whatever the camera; so plants grown from these equal the plants any camera grows there
// (tests/terrain/seed_region_test.cpp checks it against the tessellator from two cameras).
//
// The descent starts at the root triangles (the grid's root-zoom tiles covering `roots`) and
// prunes every triangle whose bounding box in grid coordinates misses the box: cost ∝ the
// triangles in the box plus their ancestors.

#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "geo/bounds.h"
#include "geo/local_frame.h"
#include "geo/xyz_tiles.h"
#include "terrain/bintree.h"
#include "terrain/resident_heights.h"

namespace vegstream::terrain {

// Which seed triangles belong to a box.
enum class RegionSelect {
  Centroid,  // the centroid lies in the box (west ≤ lon < east, south < lat ≤ north, half-open in
             // grid coordinates): adjacent boxes share no triangle and miss none
  Overlap,   // the triangle's bounding box (grown by one grid unit) meets the box: every triangle
             // with ground in the box, for callers that then keep the plants inside it
};

struct RegionSeedTriangle {
  TriPath path;
  TriCorners corners{};
  uint64_t key = 0;                   // seedKey(path)
  std::array<glm::dvec3, 3> world{};  // apex, left, right in the local ENU frame (m)
  float plantCount = 0.0f;            // N = densityM2 × the triangle's ground area
};

struct SeedRegion {
  std::vector<RegionSeedTriangle> triangles;  // in depth-first order from the roots (deterministic)
  uint64_t nodataSkipped = 0;                 // seed triangles in the box with a nodata vertex
};

struct SeedRegionQuery {
  geo::GeoBounds box;         // lon/lat (WGS 84), not across the antimeridian
  int seedLevel = 0;          // seedLevelFor(grid, …), as the tessellator uses
  double densityM2 = 10.0;  // full density: N = densityM2 × area (SeedOptions::groundDensityM2)
  RegionSelect select = RegionSelect::Centroid;
};

// The seed triangles of `query.box` over the root tiles `roots` (at grid.rootZoom()), heights
// from `heights` (whatever is resident there: a nodata vertex drops the triangle).
SeedRegion seedTrianglesIn(const BintreeGrid& grid, const geo::TileRange& roots, const geo::LocalFrame& frame,
                           ResidentHeights& heights, const SeedRegionQuery& query);

// The same triangles' count, without heights (cheap: grid arithmetic only), for size checks.
uint64_t countSeedTrianglesIn(const BintreeGrid& grid, const geo::TileRange& roots, const SeedRegionQuery& query);

// A vertex as RoamMesh makes it (roam_mesh.cpp newVertex/applySample): base + up · h; NaN
// coordinates when the height is nodata.
glm::dvec3 groundVertex(const BintreeGrid& grid, const geo::LocalFrame& frame, ResidentHeights& heights, GridPoint p);

}  // namespace vegstream::terrain
