#pragma once
// View-independent stands of trees (issue 20; stands, issue 41 item 4). Core seed
// ../shared/seeds/001_3eca9f2c7752e4fb.txt §2.2 (every random number a Philox word of the seed's
// identity, so placement depends on nothing but the ground) and §3.3 (species chosen by the colour
// score of the imagery under the seed, two best competing by eq. 16–18, s′ modulating the size).
// The seed's plants are seeded per seed triangle of a fixed bintree level; trees get this
// project's own coarser seed level instead: a square grid anchored in the dataset's local ENU
// frame, at most one tree per cell (vegetation/canopy_cells.h relies on it), standing in its cell.
//
// The grid (treeGridFor): cells of cellM = 100 √(0.9 / D) metres, D the densest tree species'
// trees per hectare, so that species keeps about 90 % of its cells. Cell (cx, cy) covers
// [cx·cellM, (cx + 1)·cellM) × [cy·cellM, (cy + 1)·cellM). Blocks of kClumpBlockCells² cells
// carry the clumps.
//
// Per cell, every draw keyed by (cx, cy) or its block alone (so a cell's tree is a pure function
// of the cells around it and the ground: local and view-independent):
//   position   a uniform point u of the cell pulled by kClumpPull towards the nearest parent point
//              (one uniform point per block; the 3 × 3 blocks around u), that parent clamped into
//              the cell first (a Neyman–Scott-like clump, J. Neyman and E. L. Scott, JRSS B 20,
//              1958). The nearest parent, not the block's own: cells pulled towards their own
//              block's parent gather about every block's centre — clumps on a 21 m lattice, rows
//              from above. Half way (0.5): the cell's points pulled to either side then tile it
//              evenly, where 0.35 gathered them in the middle (another lattice, at 7 m). The
//              ground there (TreeGroundAt: colour, NDVI, height). No ground (outside the data,
//              no imagery): no tree.
//   species    chooseSpecies over the whole catalog (species_choice.h: grass, gravel, bare soil
//              and trees compete as they do for plants) at hsvFromLinear(ground colour) with z;
//              a winner that is not a tree (or none): no tree. Else which tree: chooseTreeSpecies
//              (tree_niche.h: colour plus the species' niche in elevation, slope and relief) with
//              its own z; s′ stays the first choice's (the tree stand's border, not the species').
//   stand      kept with probability treeStandShare(C) (species_choice.h), C = canopyCoverOf the
//              two best (the imagery's canopy cover: 1 where both are trees, the tree's share where
//              one is): a tree stands where the colour clearly says forest, thinning out across an
//              even edge, and not in a meadow whose colour gives the forest a 15 % share (its
//              plants grow there instead).
//   keep       with probability min(1, p · kThinningMakeUp) · (1 + kGapAmplitude (1 − p) g), p =
//              density_ha(s) · cellM² / 10⁴ the imagery's density (the species it picks), g the gap
//              field (bilinear value noise over the blocks' corners, −1 … 1): stands get clumps
//              and gaps, deepest where the imagery's stand is sparse; kThinningMakeUp gives back
//              the share the thinning below takes (measured: density_ha holds within 5 %).
//   size       treeSizeOf: a log-normal height per species (median √(min·max of height_m) scaled
//              by s′, σ = kTreeHeightSigma: CV ≈ 0.3), clamped to [kTreeHeightFloor · min · 0.6,
//              max]; the crown scales with height as (h / median)^kCrownHeightExponent times its
//              own log-normal spread, clamped likewise into width_m. Then the canopy closes as
//              the imagery says (closedCrownM): crowns grow by C of the way to a median of
//              kCrownClosure times the species' closed-stand spacing 100 / √density_ha — trees
//              of closed forest reach their neighbours, those at the edge keep their open-grown
//              crowns (issue 41 item 6).
//   seed       one Philox word: the model variant, yaw, lean and branch angles (tree_model.h).
// Then Matérn type II thinning (B. Matérn, Spatial Variation, 1960; the taller tree as the mark):
// a cell's candidate goes when a candidate of one of its 8 neighbours, taller (ties: the larger
// seed), stands closer than max(treeSpacingM) of the two — spacing_m for a full-width crown, less
// for a smaller one: the spacing depends on size. Thinned candidates still suppress (type II), so
// every decision reads one ring of cells only.
// A renderer placing the cells tile by tile and `vegstream plants` placing a box get the same
// trees, bit for bit (tests/vegetation/tree_placement_test.cpp). Measured on 9 ha of the Kolob
// plateau's forest: vegetation/README.md.

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "vegetation/species_catalog.h"
#include "vegetation/tree_niche.h"
#include "vegetation/tree_types.h"

namespace vegstream::vegetation {

// The ground under a candidate tree, in the dataset's local ENU frame.
struct TreeGroundSample {
  bool valid = false;         // false: no tree here (outside the data, no imagery or heights)
  glm::vec3 linearRgb{0.0f};  // the imagery colour, linear RGB (decoded from sRGB, bilinear)
  float ndvi = kNoNdvi;       // kNoNdvi where the dataset has none
  double heightM = 0.0;       // the ground's z in the local frame
  TreeSite site;              // elevation, slope and relief there (tree_niche.h; NaN: unknown)
  // The species the landcover class here allows (landcover_species.h); all where the dataset has
  // no landcover layer or no class here.
  SpeciesMask allowed = kAllSpecies;
};
// (x, y): local ENU metres. Called once per cell that could hold a tree; must be a pure function
// of (x, y) for the placement to be view-independent.
using TreeGroundAt = std::function<TreeGroundSample(double x, double y)>;

struct TreeGrid {
  double cellM = 0.0;    // cell side, metres
  double marginM = 0.0;  // the largest spacing_m (the hard core of two full-width crowns)
};

inline constexpr int32_t kClumpBlockCells = 3;    // a clump block is 3 × 3 cells (21 m for the default catalog)
inline constexpr double kClumpPull = 0.5;         // the share of the way to the nearest parent point
inline constexpr float kGapAmplitude = 0.3f;      // the gap field's keep factor spans 1 ± this
inline constexpr float kThinningMakeUp = 1.09f;   // keep share raised by what thinning takes (measured)
inline constexpr float kTreeHeightSigma = 0.3f;   // log-normal σ of a species' heights
inline constexpr float kTreeHeightFloor = 0.5f;   // heights and crowns no less than this share of the least
inline constexpr float kCrownHeightExponent = 0.8f;  // crown ∝ height^0.8
inline constexpr float kCrownSigma = 0.1f;        // log-normal σ of the crown about its allometric width

struct TreeSize {
  float heightM = 0.0f, crownM = 0.0f;
};
// A tree's size from two standard normal draws (zHeight, zCrown) and its s′ (above).
TreeSize treeSizeOf(const Species& sp, float sPrime, float zHeight, float zCrown);

// The crown of a tree whose imagery says canopy cover `cover` (0 … 1): crownM · (1 + cover ·
// (g − 1)), g = max(1, fill / m), m = √(width_m.min · width_m.max) · sPrimeFactor(kSPrimeWidthLo,
// s′) the median crown treeSizeOf draws about, fill = min(kCrownClosure · 100 /
// √density_ha, kClosedCrownCap · width_m.max), and no wider than that cap. In closed forest the
// species' median crown becomes `fill`: crowns touch (the stand's spacing times kCrownClosure,
// the overlap a near-regular stand needs to hide the ground between three crowns) and keep their
// spread and their allometry with height; no crown passes 1.5 times the species' widest
// open-grown one (a woodland species of sparse stands does not balloon where its colour says
// closed). The hard core below keeps to the open-grown size.
inline constexpr float kCrownClosure = 1.7f;
inline constexpr float kClosedCrownCap = 1.5f;
float closedCrownM(const Species& sp, float crownM, float cover, float sPrime);

// The least distance a tree keeps to a shorter neighbour: spacing_m · crownM / width_m.max, for
// open-grown crowns (at most width_m.max; the closed crown comes after the hard core).
float treeSpacingM(const Species& sp, float crownM);

// The catalog's grid; contract: the catalog has a tree species (hasTrees).
TreeGrid treeGridFor(const SpeciesCatalog& catalog);

// The cell holding local point (x, y) on one axis: floor(x / cellM).
int32_t treeCellOf(const TreeGrid& grid, double x);

// The trees of cells [cx0, cx1) × [cy0, cy1) appended to `out`, row by row (cy outer, cx inner).
// Contract: the grid is treeGridFor(catalog), cx0 ≤ cx1, cy0 ≤ cy1.
void placeTreesInCells(const SpeciesCatalog& catalog, const TreeGrid& grid, int32_t cx0, int32_t cy0, int32_t cx1,
                       int32_t cy1, const TreeGroundAt& ground, std::vector<PlacedTree>& out);

}  // namespace vegstream::vegetation
