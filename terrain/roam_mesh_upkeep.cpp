// The ROAM bintree's upkeep (roam_mesh.h): resampling the vertices under a tile whose heights
// changed, and the checks the tests use (leaves, conformity). The
// splits and merges themselves are in roam_mesh.cpp, the compaction in roam_mesh_compaction.cpp (Duchaineau et al. 1997 §4, seed
// 001_3eca9f2c7752e4fb.txt §3.1).
#include "terrain/roam_mesh.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>

#include <glm/geometric.hpp>

namespace vegstream::terrain {

void RoamMesh::resampleNode(uint32_t t, const geo::TileId& tile, uint32_t lo[2], uint32_t hi[2]) {
  const TriCorners c = corners(t);
  const uint32_t minX = std::min({c.apex.x, c.left.x, c.right.x}), maxX = std::max({c.apex.x, c.left.x, c.right.x});
  const uint32_t minY = std::min({c.apex.y, c.left.y, c.right.y}), maxY = std::max({c.apex.y, c.left.y, c.right.y});
  if (maxX < lo[0] || minX > hi[0] || maxY < lo[1] || minY > hi[1]) return;
  RoamNode& n = nodes_[t];
  if (grid_.squareZoom(n.path.level) >= tile.z) n.thickness = thicknessOf(t);
  updateRadius(t);  // its vertices may have moved
  expire(t);
  markDrawnChanged(t);
  if (n.isLeaf()) return;
  RoamVertex& m = vertices_[n.mid];
  if (m.grid.x >= lo[0] && m.grid.x <= hi[0] && m.grid.y >= lo[1] && m.grid.y <= hi[1]) {
    const HeightSample s = heights_->sample(m.grid);
    if (s.sourceZoom != m.sourceZoom || !(s.heightM == m.heightM)) applySample(m, s, true);
  }
  const uint32_t ch = n.child;
  resampleNode(ch, tile, lo, hi);
  resampleNode(ch + 1, tile, lo, hi);
  nodes_[t].thickness = nestedThickness(t);  // post-order: the children are up to date
}

void RoamMesh::resample(const geo::TileId& tile) {
  if (tile.z > grid_.maxZoom()) return;
  const int shift = grid_.gridZoom() - tile.z;
  uint32_t lo[2] = {uint32_t(tile.x) << shift, uint32_t(tile.y) << shift};
  uint32_t hi[2] = {uint32_t(tile.x + 1) << shift, uint32_t(tile.y + 1) << shift};
  for (uint32_t v : cornerVertices_) {
    RoamVertex& x = vertices_[v];
    if (x.grid.x >= lo[0] && x.grid.x <= hi[0] && x.grid.y >= lo[1] && x.grid.y <= hi[1]) sampleVertex(x, true);
  }
  for (uint32_t r : roots_) resampleNode(r, tile, lo, hi);
}

std::vector<uint32_t> RoamMesh::leaves() const {
  std::vector<uint32_t> out, stack(roots_.rbegin(), roots_.rend());
  while (!stack.empty()) {
    const uint32_t t = stack.back();
    stack.pop_back();
    if (nodes_[t].isLeaf()) {
      out.push_back(t);
    } else {
      stack.push_back(nodes_[t].child + 1);
      stack.push_back(nodes_[t].child);
    }
  }
  return out;
}

uint64_t RoamMesh::conformityViolations() const {
  uint64_t bad = 0;
  const std::vector<uint32_t> all = leaves();
  // The forest's outer boundary, in grid units.
  uint32_t minX = UINT32_MAX, minY = UINT32_MAX, maxX = 0, maxY = 0;
  for (uint32_t v : cornerVertices_) {
    minX = std::min(minX, vertices_[v].grid.x);
    maxX = std::max(maxX, vertices_[v].grid.x);
    minY = std::min(minY, vertices_[v].grid.y);
    maxY = std::max(maxY, vertices_[v].grid.y);
  }
  auto onBoundary = [&](GridPoint a, GridPoint b) {
    return (a.x == b.x && (a.x == minX || a.x == maxX)) || (a.y == b.y && (a.y == minY || a.y == maxY));
  };
  for (uint32_t t : all) {
    const RoamNode& n = nodes_[t];
    const std::array<std::array<uint32_t, 2>, 3> edges{{{n.v[1], n.v[2]}, {n.v[0], n.v[1]}, {n.v[0], n.v[2]}}};
    const std::array<uint32_t, 3> links{n.base, n.left, n.right};
    for (int e = 0; e < 3; ++e) {
      const uint32_t o = links[size_t(e)];
      const auto& edge = edges[size_t(e)];
      if (o == kNoNode) {
        if (!onBoundary(vertices_[edge[0]].grid, vertices_[edge[1]].grid)) ++bad;
        continue;
      }
      const RoamNode& m = nodes_[o];
      if (!m.isLeaf()) {
        ++bad;
        continue;
      }  // a T-junction: the neighbour is split along our edge
      const std::array<std::array<uint32_t, 2>, 3> oe{{{m.v[1], m.v[2]}, {m.v[0], m.v[1]}, {m.v[0], m.v[2]}}};
      const std::array<uint32_t, 3> ol{m.base, m.left, m.right};
      bool found = false;
      for (int k = 0; k < 3; ++k) {
        if (ol[size_t(k)] != t) continue;
        const auto& x = oe[size_t(k)];
        found = (x[0] == edge[0] && x[1] == edge[1]) || (x[0] == edge[1] && x[1] == edge[0]);
      }
      if (!found) ++bad;
    }
  }
  return bad;
}

}  // namespace vegstream::terrain
