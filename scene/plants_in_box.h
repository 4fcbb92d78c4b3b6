#pragma once
// Every plant the full density grows in a lon/lat box — the CPU reference of what a flight draws
// there, as a library function (`vegstream plants` prints it; tests and tools call it). Core
// seed ../shared/seeds/001_3eca9f2c7752e4fb.txt §2.2 seeding, §3.1 seed triangles, §3.3 species
// from the imagery colour, §3.4 clusters.
//
// Full density: every seed triangle (terrain/seed_region.h) gets n_max = SeedOptions::maxPlants
// plants, i.e. what a camera close enough grows; a plant depends only on its triangle and index,
// so the result depends on the ground alone, never on a camera, and a box's plants are exactly
// the plants of any larger box that lie in it. A plant is in the box when
// lon0 ≤ lon < lon1 and lat0 ≤ lat < lat1 (half-open: adjacent boxes share none).
//
// The ground is read as a settled flight reads it: the dataset (a directory or an http(s) URL)
// through streaming's tile source and TileStreamer, heights through terrain's ResidentHeights
// over the tiles the streamer made resident (scene/settled_tiles.h), in the flight's grid, seed
// level and local frame — so the positions are those a flight computes, bit for bit.
//
// Plants come in the seed triangles' depth-first order and each triangle's sequence order.

#include <cstdint>
#include <string>
#include <vector>

#include "core/result.h"
#include "geo/bounds.h"
#include "geo/geodetic.h"
#include "scene/trees_in_box.h"
#include "vegetation/species_catalog.h"

namespace vegstream::scene {

struct BoxPlant {
  geo::Geodetic at;        // root: lat, lon (WGS 84 degrees) and the ground height there (m)
  uint32_t species = 0;    // index into the catalog
  float heightM = 0.0f;    // full-size plant height
  float stiffness = 0.0f;  // k′
  float sPrime = 0.0f;     // eq. 18
};

struct PlantsInBox {
  std::vector<BoxPlant> plants;
  std::string datasetName;  // dataset.json's name
  int seedLevel = 0;        // the bintree level of the seed triangles
  uint64_t seedTriangles = 0, nodataSkipped = 0;
};

struct PlantsInBoxOptions {
  uint32_t clusterSize = 8;        // C of §3.4, 1 … kMaxClusterSize
  uint64_t maxPlants = 5'000'000;  // a box that grows more is refused (InvalidInput)
  // How errors name the box and the limit, so a caller's message names its own inputs
  // (`vegstream plants` passes "--bbox 1,2,3,4" and "--max-plants").
  std::string boxName = "box";
  std::string maxPlantsName = "the plant limit";
  // The trees whose crowns the plants thin under (vegetation/canopy_cells.h), as a flight draws
  // them: those over the box and a crown's reach around it (scene/trees_in_box.h). Empty: none.
  std::vector<BoxCrown> crowns;
};

// Errors: NotFound / InvalidInput for the dataset (missing, bad dataset.json, no imagery, a
// corrupt tile: named), InvalidInput naming boxName for a box outside the dataset or one that
// grows more than maxPlants (saying how many), Unsupported for a dataset across the
// antimeridian, Io when tiles cannot be read.
Result<PlantsInBox> plantsInBox(const std::string& dataset, const geo::GeoBounds& box,
                                const vegetation::SpeciesCatalog& catalog, const PlantsInBoxOptions& options);

}  // namespace vegstream::scene
