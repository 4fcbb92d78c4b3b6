#pragma once
// The plain data trees are made of (issue 20), shared by the catalog (species_catalog.h: a tree
// species' `tree` block), the placement (tree_placement.h), the procedural models
// (tree_model.h) and the renderer, which uploads TreeVertex / TreeBranch / TreeInstanceGpu as
// they are (std430; shaders/common/tree_layout.glsl mirrors them).

#include <cstdint>
#include <limits>

#include <glm/vec3.hpp>

namespace vegstream::vegetation {

// The tree forms the procedural generator knows (catalog "form").
enum class TreeForm : uint32_t {
  Conifer = 0,    // one straight leader to the top, whorls of drooping branches, a cone of needle cards
  Broadleaf = 1,  // a trunk that forks into upward limbs, a round crown of leaf cards
};

// The most branch levels a model supports (trunk = level 0, then 1 … kMaxBranchLevels): the
// vertex shader walks at most this many ancestors (002 §4.3 uses 4 hierarchy levels in all).
inline constexpr uint32_t kMaxBranchLevels = 3;

// Where a tree species belongs on the terrain (tree_niche.h): closed ranges, ±infinity for an
// open end; the defaults accept every site.
struct TreeNiche {
  float elevationM[2] = {-std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity()};
  float slopeDeg[2] = {-std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity()};
  float reliefM[2] = {-std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity()};
};

// A tree species' model and placement parameters (catalog: the species' "tree" object; the
// species' own height_m and width_m give each tree's height and crown width).
struct TreeParams {
  TreeForm form = TreeForm::Conifer;
  float densityHa = 150.0f;     // trees per hectare where the species is chosen (> 0)
  float spacingM = 3.0f;        // no two trees closer than this (> 0)
  uint32_t branchLevels = 2;    // branch levels below the trunk, 2 … kMaxBranchLevels
  uint32_t branches = 24;       // level-1 branches on the trunk (≥ 3)
  uint32_t twigs = 6;           // level-2 branches per level-1 branch (≥ 1)
  float branchAngleDeg = 70.0f; // level-1 branch angle from the trunk axis, 10 … 120
  float trunkRadiusM = 0.25f;   // trunk radius at the ground, per 10 m of height (> 0)
  float taper = 0.2f;           // tip radius / root radius of every branch (α of 002 eq. 4.4), 0.1 … 0.8
  float leafSizeM = 0.6f;       // leaf or needle card length (> 0)
  uint32_t leavesPerTwig = 8;   // cards per last-level branch (≥ 1)
  float leafColour[3] = {0.09f, 0.16f, 0.06f};  // leaf albedo, linear RGB (modulated by the imagery)
  float barkColour[3] = {0.16f, 0.11f, 0.08f};  // bark albedo, linear RGB
  float translucency = 0.5f;    // share of back-lit sun the leaves pass through (002 §3), 0 … 1
  TreeNiche niche;              // where on the terrain it grows (catalog "niche"; default: anywhere)
  // false: out of the first species choice (the plants' too), so its colour never makes ground a
  // forest; it grows only where another tree species claimed the ground (tree_niche.h)
  bool claimsGround = true;
};

// One placed tree: view-independent (tree_placement.h). Position in the dataset's local ENU
// frame, metres; its ground height included.
struct PlacedTree {
  double x = 0.0, y = 0.0, z = 0.0;
  uint32_t species = 0;   // catalog index (a tree species)
  uint32_t seed = 0;      // Philox word: the model variant, yaw, lean and branch angles
  float heightM = 0.0f;   // full height
  float crownM = 0.0f;    // crown width
  float openCrownM = 0.0f;  // its crown width before the canopy closed (tree_placement.h closedCrownM)
  float sPrime = 1.0f;    // eq. 18 share of the species at its colour
  float canopyCover = 0.0f;  // the imagery's canopy cover under it (species_choice.h canopyCoverOf)
  // The imagery's colour under the tree (linear albedo): seen from afar the crowns average to it
  // (issue 39 item 5, core seed §2.4's blend into the terrain it grows from).
  glm::vec3 groundLinear{0.0f};
};

}  // namespace vegstream::vegetation
