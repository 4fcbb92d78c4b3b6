#pragma once
// Every tree in a lon/lat box (issue 20) — the trees a flight places there, as a library function
// (`vegstream plants` prints them beside the plants; tests and tools call it). The placement is
// vegetation/tree_placement.h's (core seed ../shared/seeds/001_3eca9f2c7752e4fb.txt §2.2, §3.3,
// on the tree grid, this project's coarse seed level for trees) over the ground of
// scene/tree_ground.h, in the flight's local frame (ENU at the dataset's centre, height 0).
//
// The trees depend only on the dataset, the catalog and the ground mosaic's limits (the scene's
// default, TreeGround::defaultLimits(), unless options say otherwise), never on a camera: the
// cells covering the box are placed and the trees whose position lies in the box are kept
// (lon0 ≤ lon < lon1 and lat0 ≤ lat < lat1, half-open), so a box's trees are exactly the
// trees of any larger box that lie in it. They come in the cells' row-major order (south to
// north, west to east in the local frame).

#include <cstdint>
#include <string>
#include <vector>

#include "core/result.h"
#include "geo/bounds.h"
#include "geo/geodetic.h"
#include "scene/tree_ground.h"
#include "streaming/dataset_snapshot.h"
#include "vegetation/species_catalog.h"

namespace vegstream::scene {

struct BoxTree {
  geo::Geodetic at;       // the foot of the trunk: lat, lon (WGS 84 degrees) and the ground height (m)
  uint32_t species = 0;   // index into the catalog (a tree species)
  uint32_t seed = 0;      // the tree's Philox word (model variant, yaw, lean)
  float heightM = 0.0f;   // tree height
  float crownM = 0.0f;    // crown width
  float sPrime = 0.0f;    // eq. 18
};

// A tree's crown over the ground: where its trunk stands and how wide it is.
struct BoxCrown {
  geo::Geodetic at;
  float crownM = 0.0f;
};

struct TreesInBox {
  std::vector<BoxTree> trees;
  // Every tree placed in the box and in the cells around it: the crowns that reach into the box,
  // for the plants to thin under (scene/plants_in_box.h, vegetation/canopy_cells.h).
  std::vector<BoxCrown> crowns;
  std::string datasetName;  // dataset.json's name
  double cellM = 0.0;       // the tree grid's cell side (0: the catalog has no tree species)
  uint64_t cells = 0;       // grid cells placed to cover the box
  int groundZoom = 0;       // the zoom the ground mosaic was read at
};

struct TreesInBoxOptions {
  uint64_t maxTrees = 1'000'000;  // a box that holds more is refused (InvalidInput)
  // The ground mosaic: the same limits as the flight's (SceneOptions::groundMaxPixels) give the
  // same trees.
  streaming::SnapshotLimits ground = TreeGround::defaultLimits();
  // How errors name the box and the limit (`vegstream plants`: "--bbox …", "--max-trees").
  std::string boxName = "box";
  std::string maxTreesName = "the tree limit";
};

// Errors: NotFound / InvalidInput for the dataset (missing, bad dataset.json, no imagery, a
// corrupt tile: named), InvalidInput naming boxName for a box outside the dataset or one that
// holds more than maxTrees (saying how many), Unsupported for a dataset across the antimeridian,
// Io when tiles cannot be read. A catalog without tree species gives no trees (and reads no tile).
Result<TreesInBox> treesInBox(const std::string& dataset, const geo::GeoBounds& box,
                              const vegetation::SpeciesCatalog& catalog, const TreesInBoxOptions& options);

}  // namespace vegstream::scene
