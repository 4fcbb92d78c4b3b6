#pragma once
// A tree crown's opaque core (tree_core.cpp): internal to tree_model.cpp, as tree_crowns.h.
//
// crownCoreOf measures the profile of a mesh's cards (kind 1): rings of a solid about the
// trunk inside them; empty when the mesh has too few cards. addCrownCore appends the closed solid
// (outward-facing triangles, counter-clockwise seen from outside) to `mesh` and sets
// mesh.coreFirstIndex to where its indices start: the core must be the last thing added. Its
// vertices are kind 2, on the trunk (branch 0) at x = z / trunkLength (clamped to 1), so the core
// sways with the trunk. Both levels of detail get the core of the Full cards: the same solid.

#include <vector>

#include "vegetation/tree_crowns.h"

namespace vegstream::vegetation::tree_detail {

inline constexpr uint32_t kCoreSides = 10;

struct CrownCore {
  struct Ring {
    float z;
    float radiusM[kCoreSides];  // at azimuth 2π s / kCoreSides
  };
  std::vector<Ring> rings;  // bottom to top
};

CrownCore crownCoreOf(const TreeMesh& mesh);
void addCrownCore(TreeMesh& mesh, const CrownCore& core, float trunkLength);

}  // namespace vegstream::vegetation::tree_detail
