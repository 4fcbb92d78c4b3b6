#pragma once
// View-independent tree placement (issue 20). Core seed ../shared/seeds/001_3eca9f2c7752e4fb.txt
// §2.2 (every random number a Philox word of the seed's identity, so placement depends on nothing
// but the ground) and §3.3 (species chosen by the colour score of the imagery under the seed, two
// best competing by eq. 16–18, s′ modulating the size). The seed's plants are seeded per seed
// triangle of a fixed bintree level; trees get this project's own coarser seed level instead: a
// square grid anchored in the dataset's local ENU frame, one candidate tree per cell.
//
// The grid (treeGridFor): cells of cellM = 100 √(0.9 / D) metres, D the densest tree species'
// trees per hectare, so that species keeps 90 % of its cells; margin = the largest spacing_m,
// at most 0.7 cellM (the catalog checks it, species_catalog.h). Cell (cx, cy) covers
// [cx·cellM, (cx + 1)·cellM) × [cy·cellM, (cy + 1)·cellM) and holds at most one tree, placed at
// a Philox-jittered point of [margin/2, cellM − margin/2]² inside it: two trees of neighbouring
// cells are then at least `margin` apart on the axis that separates the cells, and no two trees
// are ever closer than the largest spacing.
//
// Per cell, every draw keyed by (cx, cy) alone:
//   position   jitter (u, v) → the point above; the ground there (TreeGroundAt: colour, NDVI,
//              height). No ground (outside the data, no imagery): no tree.
//   species    chooseSpecies over the whole catalog (species_choice.h: grass, gravel, bare soil
//              and trees compete as they do for plants) at hsvFromLinear(ground colour) with z;
//              a winner that is not a tree (or none): no tree.
//   keep       with probability density_ha(s) · cellM² / 10⁴ (≤ 0.9): so trees per hectare come
//              to density_ha where the species wins.
//   size       height = mix(height_m, u_h) · sPrimeFactor(kSPrimeHeightLo, s′), crown =
//              mix(width_m, u_w) · sPrimeFactor(kSPrimeWidthLo, s′), as the plants scale by s′.
//   seed       one Philox word: the model variant, yaw, lean and branch angles (tree_model.h).
// A renderer placing the cells tile by tile and `vegstream plants` placing a box get the same
// trees, bit for bit (tests/vegetation/tree_placement_test.cpp).

#include <cstdint>
#include <functional>
#include <vector>

#include <glm/vec3.hpp>

#include "vegetation/species_catalog.h"
#include "vegetation/tree_types.h"

namespace vegstream::vegetation {

// The ground under a candidate tree, in the dataset's local ENU frame.
struct TreeGroundSample {
  bool valid = false;         // false: no tree here (outside the data, no imagery or heights)
  glm::vec3 linearRgb{0.0f};  // the imagery colour, linear RGB (decoded from sRGB, bilinear)
  float ndvi = kNoNdvi;       // kNoNdvi where the dataset has none
  double heightM = 0.0;       // the ground's z in the local frame
};
// (x, y): local ENU metres. Called once per cell that could hold a tree; must be a pure function
// of (x, y) for the placement to be view-independent.
using TreeGroundAt = std::function<TreeGroundSample(double x, double y)>;

struct TreeGrid {
  double cellM = 0.0;    // cell side, metres
  double marginM = 0.0;  // the least distance between two trees (the largest spacing_m)
};

// The catalog's grid; contract: the catalog has a tree species (hasTrees).
TreeGrid treeGridFor(const SpeciesCatalog& catalog);

// The cell holding local point (x, y) on one axis: floor(x / cellM).
int32_t treeCellOf(const TreeGrid& grid, double x);

// The trees of cells [cx0, cx1) × [cy0, cy1) appended to `out`, row by row (cy outer, cx inner).
// Contract: the grid is treeGridFor(catalog), cx0 ≤ cx1, cy0 ≤ cy1.
void placeTreesInCells(const SpeciesCatalog& catalog, const TreeGrid& grid, int32_t cx0, int32_t cy0, int32_t cx1,
                       int32_t cy1, const TreeGroundAt& ground, std::vector<PlacedTree>& out);

}  // namespace vegstream::vegetation
