// View-independent tree placement on the tree grid, this project's coarse seed level for trees
// (tree_placement.h). Core seed ../shared/seeds/001_3eca9f2c7752e4fb.txt §2.2 (Philox of the
// seed's identity: here the cell's (cx, cy)) and §3.3 (species by the colour score, eq. 16–18).
#include "vegetation/tree_placement.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include <glm/common.hpp>

#include "vegetation/philox.h"
#include "vegetation/species_choice.h"

namespace vegstream::vegetation {
namespace {

// One key per use of a cell's random words ("TRE0" …), so the draws are independent. The plants'
// placement runs the seed's 3 rounds because the GPU repeats it; trees are placed on the CPU
// only, and 10 rounds (Random123's default) keep neighbouring cells' words free of correlation.
constexpr uint32_t kPositionKey = 0x54524530u, kChoiceKey = 0x54524531u, kSizeKey = 0x54524532u,
                   kSeedKey = 0x54524533u;

Philox2x32Out cellWords(int32_t cx, int32_t cy, uint32_t key) {
  return philox2x32<10>(static_cast<uint32_t>(cx), static_cast<uint32_t>(cy), key);
}

}  // namespace

TreeGrid treeGridFor(const SpeciesCatalog& catalog) {
  assert(hasTrees(catalog));
  TreeGrid g;
  g.cellM = 100.0 * std::sqrt(double(kTreeCellShare) / double(densestTreeDensityHa(catalog)));
  g.marginM = largestTreeSpacing(catalog);
  assert(g.marginM <= double(kTreeSpacingPerCell) * g.cellM * (1.0 + 1e-6) && "species_catalog.cpp checkTrees");
  return g;
}

int32_t treeCellOf(const TreeGrid& grid, double x) {
  const double c = std::floor(x / grid.cellM);
  assert(std::abs(c) < 2147483647.0);
  return static_cast<int32_t>(c);
}

void placeTreesInCells(const SpeciesCatalog& catalog, const TreeGrid& grid, int32_t cx0, int32_t cy0, int32_t cx1,
                       int32_t cy1, const TreeGroundAt& ground, std::vector<PlacedTree>& out) {
  assert(cx0 <= cx1 && cy0 <= cy1 && grid.cellM > 0.0 && grid.marginM < grid.cellM);
  // Each species' share of its cells, and the largest: a cell whose keep draw is above every
  // share holds no tree whatever the ground, so its ground is never read (same trees, less work).
  const double cellAreaHa = grid.cellM * grid.cellM / 1e4;
  std::vector<float> keepShare(catalog.species.size(), 0.0f);
  float anyKeep = 0.0f;
  for (size_t s = 0; s < catalog.species.size(); ++s)
    if (isTree(catalog.species[s])) {
      keepShare[s] = static_cast<float>(double(catalog.species[s].tree.densityHa) * cellAreaHa);
      anyKeep = std::max(anyKeep, keepShare[s]);
    }
  const double jitterM = grid.cellM - grid.marginM;  // the span the tree's point may take in its cell
  for (int32_t cy = cy0; cy < cy1; ++cy)
    for (int32_t cx = cx0; cx < cx1; ++cx) {
      const Philox2x32Out choice = cellWords(cx, cy, kChoiceKey);
      const float keepU = u01(choice.y);
      if (!(keepU < anyKeep)) continue;
      const Philox2x32Out at = cellWords(cx, cy, kPositionKey);
      const double x = (double(cx) * grid.cellM + 0.5 * grid.marginM) + double(u01(at.x)) * jitterM;
      const double y = (double(cy) * grid.cellM + 0.5 * grid.marginM) + double(u01(at.y)) * jitterM;
      const TreeGroundSample g = ground(x, y);
      if (!g.valid) continue;
      const SpeciesChoice pick = chooseSpecies(catalog, hsvFromLinear(g.linearRgb), u01(choice.x), g.ndvi);
      if (pick.species < 0) continue;
      const auto s = static_cast<size_t>(pick.species);
      const Species& sp = catalog.species[s];
      if (!isTree(sp) || !(keepU < keepShare[s])) continue;
      const Philox2x32Out size = cellWords(cx, cy, kSizeKey);
      PlacedTree t;
      t.x = x;
      t.y = y;
      t.z = g.heightM;
      t.species = static_cast<uint32_t>(s);
      t.seed = cellWords(cx, cy, kSeedKey).x;
      t.heightM = glm::mix(sp.heightM.min, sp.heightM.max, u01(size.x)) * sPrimeFactor(kSPrimeHeightLo, pick.sPrime);
      t.crownM = glm::mix(sp.widthM.min, sp.widthM.max, u01(size.y)) * sPrimeFactor(kSPrimeWidthLo, pick.sPrime);
      t.sPrime = pick.sPrime;
      t.groundLinear = g.linearRgb;
      out.push_back(t);
    }
}

}  // namespace vegstream::vegetation
