#include "terrain/grid_mesh.h"

#include <cassert>
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace vegstream::terrain {

TerrainMesh buildGridMesh(const HeightGrid& grid, const geo::LocalFrame& frame, const GridMeshOptions& options) {
  assert(options.step >= 1);
  assert(grid.heights.size() == static_cast<size_t>(grid.width) * static_cast<size_t>(grid.height));
  const int step = options.step;
  const int cols = (grid.width - 1) / step + 1;
  const int rows = (grid.height - 1) / step + 1;
  TerrainMesh mesh;
  mesh.origin = glm::dvec3(0.0);  // the frame's origin
  mesh.vertices.resize(static_cast<size_t>(cols) * static_cast<size_t>(rows));
  std::vector<glm::dvec3> positions(mesh.vertices.size());
  std::vector<bool> valid(mesh.vertices.size());

  auto index = [cols](int c, int r) {
    return static_cast<size_t>(r) * static_cast<size_t>(cols) + static_cast<size_t>(c);
  };
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const float h = grid.at(c * step, r * step);
      const size_t i = index(c, r);
      valid[i] = !std::isnan(h);
      const double hm = valid[i] ? static_cast<double>(h) : 0.0;
      const glm::dvec2 lonLat = grid.lonLatAt(c * step, r * step);
      positions[i] = frame.toLocal({lonLat.y, lonLat.x, hm});
      mesh.vertices[i].uv = options.uv ? options.uv(lonLat.x, lonLat.y) : glm::vec2(0.0f);
      mesh.vertices[i].position = glm::vec3(positions[i] - mesh.origin);
      mesh.vertices[i].heightMsl = static_cast<float>(hm);
    }
  }
  // Normals by central differences over valid neighbours, in the local frame.
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const size_t i = index(c, r);
      auto pick = [&](int cc, int rr) {
        cc = std::clamp(cc, 0, cols - 1);
        rr = std::clamp(rr, 0, rows - 1);
        return valid[index(cc, rr)] ? positions[index(cc, rr)] : positions[i];
      };
      const glm::dvec3 east = pick(c + 1, r) - pick(c - 1, r);
      const glm::dvec3 south = pick(c, r + 1) - pick(c, r - 1);  // rows run north → south
      glm::dvec3 n = glm::cross(south, east);
      const double len = glm::length(n);
      mesh.vertices[i].normal = len > 0.0 ? glm::vec3(n / len) : glm::vec3(0, 0, 1);
    }
  }
  mesh.indices.reserve(static_cast<size_t>(cols - 1) * static_cast<size_t>(rows - 1) * 6);
  for (int r = 0; r + 1 < rows; ++r) {
    for (int c = 0; c + 1 < cols; ++c) {
      const uint32_t nw = static_cast<uint32_t>(index(c, r)), ne = static_cast<uint32_t>(index(c + 1, r));
      const uint32_t sw = static_cast<uint32_t>(index(c, r + 1)), se = static_cast<uint32_t>(index(c + 1, r + 1));
      // Counter-clockwise seen from above (east = +x, north = +y).
      if (valid[sw] && valid[se] && valid[nw]) mesh.indices.insert(mesh.indices.end(), {sw, se, nw});
      if (valid[se] && valid[ne] && valid[nw]) mesh.indices.insert(mesh.indices.end(), {se, ne, nw});
    }
  }
  return mesh;
}

}  // namespace vegstream::terrain
