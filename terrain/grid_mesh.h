#pragma once
// The foundation's terrain: a regular grid mesh over a HeightGrid, one vertex per kept sample
// (every `step`-th), placed in a local ENU frame with earth curvature. Replaced by ROAM in
// the terrain issue; kept as the reference mesh for tests.

#include <functional>

#include <glm/vec2.hpp>

#include "geo/local_frame.h"
#include "terrain/height_grid.h"
#include "terrain/terrain_mesh.h"

namespace vegstream::terrain {

struct GridMeshOptions {
  int step = 1;  // use every step-th sample in both directions (≥ 1)
  // Texture coordinates of the imagery at a longitude/latitude (degrees); none: (0, 0).
  std::function<glm::vec2(double lonDeg, double latDeg)> uv;
};

// Vertices at the grid's sample centres. Triangles touching a nodata sample are left out, so
// nodata is a hole, never a drop to zero. The mesh origin is the frame's origin.
TerrainMesh buildGridMesh(const HeightGrid& grid, const geo::LocalFrame& frame, const GridMeshOptions& options = {});

}  // namespace vegstream::terrain
