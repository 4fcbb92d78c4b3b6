// The crowns over the ground near the camera (canopy_cells.h; issue 20). The GLSL twin is
// shaders/classify.comp's canopyCover: the same float operations in the same order.
#include "vegetation/canopy_cells.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace vegstream::vegetation {

void fillCanopyTable(const TreeGrid& grid, const glm::dvec3& camera, std::span<const CanopyTree> trees,
                     CanopyTable& out) {
  assert(grid.cellM > 0.0);
  out.entries.assign(size_t{kCanopyCells} * kCanopyCells, CanopyEntry{});
  const int32_t cx = treeCellOf(grid, camera.x), cy = treeCellOf(grid, camera.y);
  out.camera = camera;
  out.header = {};
  out.header.offsetX = static_cast<float>(camera.x - grid.cellM * cx);
  out.header.offsetY = static_cast<float>(camera.y - grid.cellM * cy);
  out.header.cellM = static_cast<float>(grid.cellM);
  out.header.cellX = cx;
  out.header.cellY = cy;
  out.header.enabled = 1;
  constexpr int32_t kHalf = static_cast<int32_t>(kCanopyCells / 2);
  for (const CanopyTree& t : trees) {
    const int32_t tx = treeCellOf(grid, t.position.x), ty = treeCellOf(grid, t.position.y);
    if (tx < cx - kHalf || tx >= cx + kHalf || ty < cy - kHalf || ty >= cy + kHalf) continue;
    CanopyEntry& e = out.entries[(static_cast<uint32_t>(ty) % kCanopyCells) * kCanopyCells +
                                 static_cast<uint32_t>(tx) % kCanopyCells];
    e.x = static_cast<float>(t.position.x - camera.x);
    e.y = static_cast<float>(t.position.y - camera.y);
    e.radiusM = std::min(0.5f * t.crownM, out.header.cellM);  // the 3 × 3 lookup reaches a cell
    e.cell = canopyCellId(tx, ty);
  }
}

float canopyCover(const CanopyTable& table, glm::vec2 p) {
  const CanopyHeader& h = table.header;
  if (h.enabled == 0 || table.entries.empty()) return 0.0f;
  const int32_t cx = h.cellX + static_cast<int32_t>(std::floor((p.x + h.offsetX) / h.cellM));
  const int32_t cy = h.cellY + static_cast<int32_t>(std::floor((p.y + h.offsetY) / h.cellM));
  float cover = 0.0f;
  for (int32_t dy = -1; dy <= 1; ++dy)
    for (int32_t dx = -1; dx <= 1; ++dx) {
      const int32_t x = cx + dx, y = cy + dy;
      const CanopyEntry& e = table.entries[(static_cast<uint32_t>(y) % kCanopyCells) * kCanopyCells +
                                           static_cast<uint32_t>(x) % kCanopyCells];
      if (e.cell != canopyCellId(x, y)) continue;
      const float ex = p.x - e.x, ey = p.y - e.y;
      const float d = std::sqrt(ex * ex + ey * ey);
      const float t = std::clamp((e.radiusM - d) / (kCanopyEdge * e.radiusM), 0.0f, 1.0f);
      cover = std::max(cover, t * t * (3.0f - 2.0f * t));
    }
  return cover;
}

}  // namespace vegstream::vegetation
