#pragma once
// The crowns over the ground near the camera, so that plants thin under a tree (issue 20: "grass
// thins under a crown"). The tree grid (tree_placement.h) holds at most one tree per cell, and a
// crown's radius is at most a cell: a point is under the crowns of the trees in the 3 × 3 cells
// around its own. The table holds kCanopyCells × kCanopyCells cells about the camera's, each
// entry the tree of one cell, addressed toroidally (cell mod kCanopyCells): its centre relative
// to the camera, its crown radius and which cell it is — an entry of another cell, or empty, is
// no crown. Positions relative to the camera in float, as the seed triangles' vertices
// (SeedTriangleGpu): the GPU's classify (shaders/classify.comp) and the CPU's (plant_seeding.cpp
// through canopyCover) compute the same cover with the same operations.
//
// The window reaches past the default seeding horizon (250 m), so a plant's cover does not depend
// on where the camera is: a catalog whose plants reach farther than kCanopyCells / 2 cells has
// them unthinned out there. Only the trees drawn (tiles with pages) cast a crown.
//
// The cover of a point at distance d from a crown of radius R is 1 inside 0.6 R, then falls to 0
// at R (smoothstep); the plants' group there is dropped with probability kCanopyThinning × cover
// (its own Philox draw, philox_slot::kCanopy): the ground under a crown is shaded and bare.

#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "vegetation/tree_placement.h"

namespace vegstream::vegetation {

inline constexpr uint32_t kCanopyCells = 90;  // 90 × 5.88 m: ±265 m about the camera's cell, past the plants' 250 m
inline constexpr float kCanopyThinning = 0.85f;       // the share of groups dropped under a crown's middle
inline constexpr float kCanopyEdge = 0.4f;            // the outer share of the radius the cover falls over
inline constexpr uint32_t kNoCanopyCell = 0xFFFFFFFFu;

// std430 (shaders/classify.comp's CanopyEntry).
struct CanopyEntry {
  float x = 0.0f, y = 0.0f;  // the crown's centre relative to the camera, m
  float radiusM = 0.0f;
  uint32_t cell = kNoCanopyCell;  // canopyCellId of the cell it belongs to
};
static_assert(sizeof(CanopyEntry) == 16);

inline uint32_t canopyCellId(int32_t cx, int32_t cy) {
  return (static_cast<uint32_t>(cx) & 0xFFFFu) | (static_cast<uint32_t>(cy) << 16);
}

// std430 header of the GPU buffer, followed by the entries.
struct CanopyHeader {
  float offsetX = 0.0f, offsetY = 0.0f;  // the camera's position in its cell, m (0 … cell)
  float cellM = 0.0f;
  uint32_t enabled = 0;  // 0: no crowns (no table this frame)
  int32_t cellX = 0, cellY = 0;  // the camera's cell
  uint32_t pad[2] = {0, 0};
};
static_assert(sizeof(CanopyHeader) == 32);

struct CanopyTable {
  glm::dvec3 camera{0.0};  // what the entries are relative to (the seed triangles' camera)
  CanopyHeader header;
  std::vector<CanopyEntry> entries;  // kCanopyCells², empty: no crowns
};

// One tree for canopyTable: its position in the local ENU frame and its crown width.
struct CanopyTree {
  glm::dvec3 position;
  float crownM;
};

// The table about `camera` (local ENU) of `trees` (any order; those outside the table's cells
// are left out; a crown's radius is clamped to the cell).
void fillCanopyTable(const TreeGrid& grid, const glm::dvec3& camera, std::span<const CanopyTree> trees,
                     CanopyTable& out);

// The cover (0 … 1) at a point `p` relative to the table's camera; 0 for an empty table.
float canopyCover(const CanopyTable& table, glm::vec2 p);

}  // namespace vegstream::vegetation
