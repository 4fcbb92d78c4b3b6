// The crown's projected area (crown_projection.h): the mesh's triangles rasterised straight down
// onto a grid, each cell counted once when its centre lies in any triangle (an edge-function
// test, as a rasteriser's), then the radius of the disk of that area.
#include "vegetation/crown_projection.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <vector>

namespace vegstream::vegetation {
namespace {

struct Point {
  double x = 0.0, y = 0.0;
};

double edge(Point a, Point b, Point p) { return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x); }

// Marks the cells whose centres lie in triangle abc (either winding; degenerate: none).
void markTriangle(Point a, Point b, Point c, double x0, double y0, double cell, int cells, std::vector<uint8_t>& hit) {
  const double area = edge(a, b, c);
  if (std::abs(area) < 1e-12) return;
  const double sign = area > 0.0 ? 1.0 : -1.0;
  const auto first = [&](double v, double o) {
    return std::clamp(static_cast<int>(std::ceil((v - o) / cell - 0.5)), 0, cells);
  };
  const auto last = [&](double v, double o) {
    return std::clamp(static_cast<int>(std::floor((v - o) / cell - 0.5)), -1, cells - 1);
  };
  const int i0 = first(std::min({a.x, b.x, c.x}), x0), i1 = last(std::max({a.x, b.x, c.x}), x0);
  const int j0 = first(std::min({a.y, b.y, c.y}), y0), j1 = last(std::max({a.y, b.y, c.y}), y0);
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) {
      const Point p{x0 + (i + 0.5) * cell, y0 + (j + 0.5) * cell};
      if (sign * edge(a, b, p) >= 0.0 && sign * edge(b, c, p) >= 0.0 && sign * edge(c, a, p) >= 0.0)
        hit[static_cast<size_t>(j) * static_cast<size_t>(cells) + static_cast<size_t>(i)] = 1;
    }
}

}  // namespace

float crownProjectionRadius(const TreeMesh& mesh, int cells) {
  assert(cells >= 16 && cells <= 1024);
  assert(mesh.indices.size() % 3 == 0);
  if (mesh.indices.empty()) return 0.0f;
  double reach = 0.0;
  for (const TreeVertex& v : mesh.vertices)
    reach = std::max({reach, std::abs(double(v.position[0])), std::abs(double(v.position[1]))});
  if (!(reach > 0.0)) return 0.0f;
  const double cell = 2.0 * reach / cells, x0 = -reach, y0 = -reach;
  std::vector<uint8_t> hit(static_cast<size_t>(cells) * static_cast<size_t>(cells), 0);
  const auto at = [&](uint32_t k) {
    assert(k < mesh.vertices.size());
    return Point{mesh.vertices[k].position[0], mesh.vertices[k].position[1]};
  };
  for (size_t t = 0; t < mesh.indices.size(); t += 3)
    markTriangle(at(mesh.indices[t]), at(mesh.indices[t + 1]), at(mesh.indices[t + 2]), x0, y0, cell, cells, hit);
  const double covered = static_cast<double>(std::count(hit.begin(), hit.end(), uint8_t{1})) * cell * cell;
  return static_cast<float>(std::sqrt(covered / 3.14159265358979323846));
}

}  // namespace vegstream::vegetation
