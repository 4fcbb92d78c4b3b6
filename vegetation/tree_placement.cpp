// Stands of trees on the tree grid, this project's coarse seed level for trees (tree_placement.h).
// Core seed ../shared/seeds/001_3eca9f2c7752e4fb.txt §2.2 (Philox of the seed's identity: here the
// cell's (cx, cy) and its clump block's) and §3.3 (species by the colour score, eq. 16–18).
// Clumps: a Neyman–Scott-like pull of each cell's point towards its block's parent point and a
// value-noise gap field on the keep share; spacing: Matérn type II thinning (B. Matérn, "Spatial
// variation", Medd. Statens Skogsforskningsinstitut 49(5), 1960) with a hard core that grows with
// the trees' crowns, the taller tree winning; sizes: a log-normal height per species with the
// crown scaling allometrically with height (H. S. Horn, "The adaptive geometry of trees", 1971,
// for the crown–height power law). Every draw is a pure function of cells, so placement is local.
#include "vegetation/tree_placement.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include <glm/common.hpp>

#include "vegetation/philox.h"
#include "vegetation/species_choice.h"
#include "vegetation/tree_niche.h"

namespace vegstream::vegetation {
namespace {

// One key per use of a cell's random words ("TRE0" …), so the draws are independent. Trees are
// placed on the CPU only; 10 rounds (Random123's default) keep neighbouring cells' words free of
// correlation.
constexpr uint32_t kPositionKey = 0x54524530u, kChoiceKey = 0x54524531u, kSizeKey = 0x54524532u,
                   kSeedKey = 0x54524533u, kClumpKey = 0x54524534u, kGapKey = 0x54524535u,
                   kNicheKey = 0x54524536u, kStandKey = 0x54524537u;

Philox2x32Out cellWords(int32_t cx, int32_t cy, uint32_t key) {
  return philox2x32<10>(static_cast<uint32_t>(cx), static_cast<uint32_t>(cy), key);
}

int32_t floorDiv(int32_t a, int32_t b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

// The gap field at cell (cx, cy): bilinear value noise over the clump blocks' corners, −1 … 1.
float gapField(int32_t cx, int32_t cy) {
  const int32_t bx = floorDiv(cx, kClumpBlockCells), by = floorDiv(cy, kClumpBlockCells);
  const float fx = (float(cx - bx * kClumpBlockCells) + 0.5f) / float(kClumpBlockCells);
  const float fy = (float(cy - by * kClumpBlockCells) + 0.5f) / float(kClumpBlockCells);
  auto corner = [](int32_t x, int32_t y) { return u01(cellWords(x, y, kGapKey).x); };
  const float v = glm::mix(glm::mix(corner(bx, by), corner(bx + 1, by), fx),
                           glm::mix(corner(bx, by + 1), corner(bx + 1, by + 1), fx), fy);
  return 2.0f * v - 1.0f;
}

// The keep share of a species whose plain share is `share`, at gap field value `gap`: gaps are
// deepest where the imagery's stand is sparse (no room for them where it fills every cell).
float keepWith(float share, float gap) {
  return std::min(share * kThinningMakeUp, 1.0f) * (1.0f + kGapAmplitude * (1.0f - std::min(share, 1.0f)) * gap);
}

// The candidate's point (tree_placement.h: position): uniform in its cell, pulled towards the
// nearest clump parent of the 3 × 3 blocks around it, as seen from the cell (clamped into it).
void candidatePoint(const TreeGrid& grid, int32_t cx, int32_t cy, double& x, double& y) {
  const Philox2x32Out at = cellWords(cx, cy, kPositionKey);
  const double block = grid.cellM * kClumpBlockCells;
  const double x0 = double(cx) * grid.cellM, y0 = double(cy) * grid.cellM;
  const double ux = x0 + double(u01(at.x)) * grid.cellM, uy = y0 + double(u01(at.y)) * grid.cellM;
  const auto bx = static_cast<int32_t>(std::floor(ux / block)), by = static_cast<int32_t>(std::floor(uy / block));
  double px = ux, py = uy, best = INFINITY;
  for (int32_t j = by - 1; j <= by + 1; ++j)
    for (int32_t i = bx - 1; i <= bx + 1; ++i) {
      const Philox2x32Out parent = cellWords(i, j, kClumpKey);
      const double qx = (double(i) + double(u01(parent.x))) * block, qy = (double(j) + double(u01(parent.y))) * block;
      const double d = (qx - ux) * (qx - ux) + (qy - uy) * (qy - uy);
      if (d < best) best = d, px = qx, py = qy;
    }
  const double inset = 1e-3 * grid.cellM;  // strictly inside the cell: treeCellOf(x) is the cell
  const double tx = std::clamp(px, x0 + inset, x0 + grid.cellM - inset);
  const double ty = std::clamp(py, y0 + inset, y0 + grid.cellM - inset);
  x = std::clamp(ux + kClumpPull * (tx - ux), x0 + inset, x0 + grid.cellM - inset);
  y = std::clamp(uy + kClumpPull * (ty - uy), y0 + inset, y0 + grid.cellM - inset);
}

// A standard normal from two words (Box–Muller).
float normalOf(uint32_t a, uint32_t b) {
  const float u = (float(a >> 8) + 0.5f) * (1.0f / 16777216.0f);
  return std::sqrt(-2.0f * std::log(u)) * std::cos(6.28318530717958647692f * u01(b));
}

// The cell's tree before thinning, or false.
bool candidateOf(const SpeciesCatalog& catalog, const TreeGrid& grid, std::span<const float> keepShare, float anyKeep,
                 int32_t cx, int32_t cy, const TreeGroundAt& ground, PlacedTree& t) {
  const Philox2x32Out choice = cellWords(cx, cy, kChoiceKey);
  const float keepU = u01(choice.y);
  if (!(keepU < anyKeep)) return false;  // above every species' keep share: no need to read the ground
  const float gap = gapField(cx, cy);
  double x = 0.0, y = 0.0;
  candidatePoint(grid, cx, cy, x, y);
  const TreeGroundSample g = ground(x, y);
  if (!g.valid) return false;
  const GroundColour colour = calibratedGround(catalog.calibration, g.linearRgb);
  const SpeciesCandidates cands = speciesCandidates(catalog, colour.hsv, g.ndvi, colour.exg, g.allowed);
  const SpeciesChoice pick = chooseAmong(catalog, cands, u01(choice.x));
  if (pick.species < 0 || !isTree(catalog.species[static_cast<size_t>(pick.species)])) return false;
  const float cover = canopyCoverOf(catalog, cands);
  if (!(u01(cellWords(cx, cy, kStandKey).x) < treeStandShare(cover))) return false;
  const SpeciesChoice tree =
      chooseTreeSpecies(catalog, pick.species, colour, g.ndvi, g.site, u01(cellWords(cx, cy, kNicheKey).x), g.allowed);
  const auto s = static_cast<size_t>(tree.species >= 0 ? tree.species : pick.species);
  const Species& sp = catalog.species[s];
  if (!(keepU < keepWith(keepShare[s], gap))) return false;
  const Philox2x32Out size = cellWords(cx, cy, kSizeKey);
  const Philox2x32Out more = cellWords(cx, cy, kSizeKey + 0x100u);
  t = PlacedTree{};
  t.x = x;
  t.y = y;
  t.z = g.heightM;
  t.species = static_cast<uint32_t>(s);
  t.seed = cellWords(cx, cy, kSeedKey).x;
  const TreeSize z = treeSizeOf(sp, pick.sPrime, normalOf(size.x, size.y), normalOf(more.x, more.y));
  t.heightM = z.heightM;
  t.crownM = z.crownM;  // open-grown: the hard core below; closed after it (placeTreesInCells)
  t.canopyCover = cover;
  t.sPrime = pick.sPrime;
  t.groundLinear = g.linearRgb;
  return true;
}

}  // namespace

TreeSize treeSizeOf(const Species& sp, float sPrime, float zHeight, float zCrown) {
  const float median = std::sqrt(sp.heightM.min * sp.heightM.max) * sPrimeFactor(kSPrimeHeightLo, sPrime);
  const float lo = kTreeHeightFloor * sp.heightM.min * kSPrimeHeightLo;
  TreeSize out;
  out.heightM = std::clamp(median * std::exp(kTreeHeightSigma * zHeight), lo, sp.heightM.max);
  const float crownMid = std::sqrt(sp.widthM.min * sp.widthM.max) * sPrimeFactor(kSPrimeWidthLo, sPrime);
  const float crown = crownMid * std::pow(out.heightM / median, kCrownHeightExponent) * std::exp(kCrownSigma * zCrown);
  out.crownM = std::clamp(crown, kTreeHeightFloor * sp.widthM.min * kSPrimeWidthLo, sp.widthM.max);
  return out;
}

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

float treeSpacingM(const Species& sp, float crownM) {
  assert(crownM <= sp.widthM.max * (1.0f + 1e-6f) && "the hard core sees open-grown crowns (treeSizeOf clamps them)");
  return sp.tree.spacingM * crownM / sp.widthM.max;
}

float closedCrownM(const Species& sp, float crownM, float cover, float sPrime) {
  assert(sp.tree.densityHa > 0.0f && sp.widthM.min > 0.0f);
  const float cap = kClosedCrownCap * sp.widthM.max;
  const float fill = std::min(kCrownClosure * 100.0f / std::sqrt(sp.tree.densityHa), cap);
  const float median = std::sqrt(sp.widthM.min * sp.widthM.max) * sPrimeFactor(kSPrimeWidthLo, sPrime);
  const float grow = std::max(fill / median, 1.0f);
  return std::min(crownM * (1.0f + std::clamp(cover, 0.0f, 1.0f) * (grow - 1.0f)), std::max(crownM, cap));
}

void placeTreesInCells(const SpeciesCatalog& catalog, const TreeGrid& grid, int32_t cx0, int32_t cy0, int32_t cx1,
                       int32_t cy1, const TreeGroundAt& ground, std::vector<PlacedTree>& out) {
  assert(cx0 <= cx1 && cy0 <= cy1 && grid.cellM > 0.0 && grid.marginM < grid.cellM);
  // Each species' share of its cells, and the most any cell may keep (the gap field's top).
  const double cellAreaHa = grid.cellM * grid.cellM / 1e4;
  std::vector<float> keepShare(catalog.species.size(), 0.0f);
  float anyKeep = 0.0f;
  for (size_t s = 0; s < catalog.species.size(); ++s)
    if (isTree(catalog.species[s])) {
      keepShare[s] = static_cast<float>(double(catalog.species[s].tree.densityHa) * cellAreaHa);
      anyKeep = std::max(anyKeep, keepWith(keepShare[s], 1.0f));
    }
  // The candidates of the cells and a ring of one around them (Matérn II reads its neighbours').
  const int32_t w = cx1 - cx0 + 2, h = cy1 - cy0 + 2;
  std::vector<PlacedTree> cand(size_t(w) * size_t(h));
  std::vector<uint8_t> has(cand.size(), 0);
  for (int32_t j = 0; j < h; ++j)
    for (int32_t i = 0; i < w; ++i) {
      const size_t k = size_t(j) * size_t(w) + size_t(i);
      has[k] = candidateOf(catalog, grid, keepShare, anyKeep, cx0 - 1 + i, cy0 - 1 + j, ground, cand[k]) ? 1 : 0;
    }
  // A candidate goes when a neighbour's, taller (ties: the larger seed), stands within the hard core.
  for (int32_t j = 1; j + 1 < h; ++j)
    for (int32_t i = 1; i + 1 < w; ++i) {
      const size_t k = size_t(j) * size_t(w) + size_t(i);
      if (!has[k]) continue;
      const PlacedTree& t = cand[k];
      bool beaten = false;
      for (int32_t dj = -1; dj <= 1 && !beaten; ++dj)
        for (int32_t di = -1; di <= 1 && !beaten; ++di) {
          const size_t n = size_t(j + dj) * size_t(w) + size_t(i + di);
          if (n == k || !has[n]) continue;
          const PlacedTree& o = cand[n];
          const bool taller = o.heightM > t.heightM || (o.heightM == t.heightM && o.seed > t.seed);
          const double core = std::max(treeSpacingM(catalog.species[t.species], t.crownM),
                                       treeSpacingM(catalog.species[o.species], o.crownM));
          beaten = taller && std::hypot(o.x - t.x, o.y - t.y) < core;
        }
      if (beaten) continue;
      out.push_back(t);
      out.back().openCrownM = t.crownM;
      out.back().crownM = closedCrownM(catalog.species[t.species], t.crownM, t.canopyCover, t.sPrime);
    }
}

}  // namespace vegstream::vegetation
