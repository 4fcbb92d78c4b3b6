#pragma once
// What the tree field (tree_field.h) did in one frame: its tiles within the horizon, placed and
// given pages, and the placement's cost. Plain data, so the frame's record holds it whole.

#include <cstdint>

namespace vegstream::scene {

struct TreeFieldFigures {
  uint32_t tilesWanted = 0, tilesDrawn = 0;  // within the horizon; with pages
  uint64_t treesDrawn = 0;                   // trees in the tiles with pages
  uint32_t pagesUsed = 0, pageCapacity = 0;
  uint32_t placed = 0;       // tiles placed this frame
  double placementMs = 0.0;  // their cost
  bool budgetBound = false;  // a wanted tile had no page: far trees fall back to the terrain's colour
};

}  // namespace vegstream::scene
