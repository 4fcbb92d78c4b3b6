#pragma once
// Internal to roam_tessellator*.cpp: the state one traversal of the bintree carries.

#include <vector>

#include "terrain/roam_tessellator.h"

namespace vegstream::terrain {

struct RoamTessellator::Walk {
  const EyeView* view = nullptr;
  const PieceSet* pieces = nullptr;
  double bound = 0.0;
  double timeS = 0.0;
  // update()
  std::vector<Candidate>* splits = nullptr;
  std::vector<Candidate>* diamonds = nullptr;
  double mergeBelow = 0.0;
  bool overBudget = false;
  // output()
  std::vector<TerrainMesh>* meshes = nullptr;
  std::vector<SeedTriangle>* seeds = nullptr;
  int untextured = -1;  // index of the mesh for leaves not yet inside a piece
};

}  // namespace vegstream::terrain
