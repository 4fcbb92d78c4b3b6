#pragma once
// Procedural tree models (issue 20): a trunk and kMaxBranchLevels ≥ levels ≥ 2 of branches as
// tapered generalized cylinders, and leaf or needle cards on the last level, built at start-up
// from a species' TreeParams and a variant seed — no asset files. Seed 002 (Habel) §4.3: every
// vertex carries its branch's index and its axial coordinate x ∈ [0, 1] along that branch; the
// branch table holds each branch's frame (t, r, s), length L, the fitted tapered-beam
// coefficients c₂, c₄ (tree_bending.h, eq. 4.7–4.8) and its resonance f = 2.55 L^−0.59
// (eq. 4.20), so the vertex shader bends the hierarchy without a skeleton update.
//
// Object space: z up, the trunk's root at the origin, the model `params`' nominal height
// (1 unit = 1 metre at modelHeightM); instances scale it to their own height.
//
// Two levels of detail from one call: Full (every branch, bark rings of 8 sides, every card) and
// Reduced (trunk and level-1 branches only, rings of 4 sides, fewer and larger cards covering the
// same crown). Impostors are rendered from Full (render/tree_impostors).

#include <cstdint>
#include <vector>

#include "vegetation/tree_types.h"

namespace vegstream::vegetation {

// GPU vertex, 48 bytes (std430, shaders/common/tree_layout.glsl).
struct TreeVertex {
  float position[3];  // object space, metres at the model's height
  uint32_t branch;    // index into TreeModel::branches (a card: the branch it hangs on)
  float normal[3];    // unit
  float along;        // x ∈ [0, 1] on its branch (a card: where it is attached)
  float uv[2];        // bark: (around 0…1, along in metres / circumference); card: [0, 1]², v along the card
  uint32_t kind;      // 0 bark, 1 leaf card, 2 the crown's opaque core
  float flutter;      // 0 at a card's stem … 1 at its tip (bark: 0)
};
static_assert(sizeof(TreeVertex) == 48);

// One branch (the trunk is branch 0, level 0), 80 bytes (std430).
struct TreeBranch {
  float origin[3];
  float length;     // L, metres
  float t[3];       // unit axis, root to tip
  float c2;         // u(x) = c₂x² + c₄x⁴, normalised so u(1) = 1 (tree_bending.h)
  float r[3];       // unit, ⟂ t
  float c4;
  float s[3];       // t × r
  float frequencyHz;  // 2.55 L^−0.59 (002 eq. 4.20)
  int32_t parent;     // −1 for the trunk
  float parentAlong;  // x on the parent where this branch starts
  uint32_t level;     // 0 trunk, 1, 2, …
  float compliance;   // tip deflection per unit wind load, in branch lengths (thin, long: more)
};
static_assert(sizeof(TreeBranch) == 80);

enum class TreeLod : uint32_t { Full = 0, Reduced = 1 };

struct TreeMesh {
  std::vector<TreeVertex> vertices;
  std::vector<uint32_t> indices;  // triangle list: bark and cards, then the crown's core
  // Where the core's triangles start (kind 2, tree_core.h): an opaque solid inside the crown,
  // drawn before everything else with early depth tests. Bark and cards are [0, coreFirstIndex).
  uint32_t coreFirstIndex = 0;
};

struct TreeModel {
  float modelHeightM = 0.0f;  // the height the model was built at (the species' mean height)
  float crownRadiusM = 0.0f;  // the largest horizontal distance of any vertex from the axis
  // The radius of the disk of the Full mesh's area seen from above (crown_projection.h): a tree
  // asking for a crown width w is drawn w / (2 · this) wide, so its crown covers its disk.
  float crownAreaRadiusM = 0.0f;
  std::vector<TreeBranch> branches;  // shared by both levels of detail (Reduced uses a subset)
  TreeMesh lod[2];                   // indexed by TreeLod
};

// Builds one variant. Deterministic: the same params and seed give the same model, bit for bit.
// Contract (asserted): params valid as species_catalog.h checks them.
TreeModel buildTreeModel(const TreeParams& params, float heightM, float crownWidthM, uint32_t variantSeed);

}  // namespace vegstream::vegetation
