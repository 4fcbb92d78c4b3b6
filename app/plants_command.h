#pragma once
// `vegstream plants DATASET --bbox lon0,lat0,lon1,lat1 [--format csv|json] [--output FILE]
//  [--species FILE] [--cluster-size C] [--max-plants N] [--max-trees N]`: every plant the full
// density grows in a lon/lat box, and every tree placed there, as CSV or JSON — the CPU reference of what a flight draws there (core seed
// ../shared/seeds/001_3eca9f2c7752e4fb.txt §2.2 seeding, §3.1 seed triangles, §3.3 species from
// the imagery colour, §3.4 clusters).
//
// Full density: every seed triangle (terrain/seed_region.h) gets n_max = SeedOptions::maxPlants
// plants, i.e. what a camera close enough grows; a plant depends only on its triangle and index,
// so the output depends on the ground alone, never on a camera, and a box's plants are exactly
// the plants of any larger box that lie in it. A plant is in the box when
// lon0 ≤ lon < lon1 and lat0 ≤ lat < lat1 (half-open: adjacent boxes share none).
//
// Rows, in the seed triangles' depth-first order and each triangle's sequence order:
//   lat, lon        WGS 84 degrees (10 decimals, about 10 µm) of the root
//   height_m        the ground at the root (m above the dataset's datum)
//   species         catalog name
//   plant_height_m  full-size height, stiffness (k′), s_prime (eq. 18)
// Then the trees (issue 20: every tree the view-independent tree placement puts there,
// scene/trees_in_box.h; in the tree grid's row-major cell order):
//   lat, lon, height_m, species   as above, at the foot of the trunk
//   tree_height_m, crown_m        the tree's height and crown width
//   s_prime                       eq. 18
// CSV: the plants' header and rows, one empty line, then the trees' header
// (lat,lon,height_m,species,tree_height_m,crown_m,s_prime) and rows. JSON is {"dataset", "bbox",
// "seed_level", "cluster_size", "plant_count", "plants": [{…}, …], "tree_count", "trees": [{…}, …]}.
// Tree species are listed only as trees (the plant seeding's rare plants of a tree species are
// left out of the plants).

#include <cstdint>
#include <string>

#include "core/log.h"

namespace CLI {
class App;
}

namespace vegstream::app {

struct PlantsOptions {
  std::string dataset;
  std::string bbox;             // lon0,lat0,lon1,lat1
  std::string format = "csv";   // csv | json
  std::string output;           // empty: stdout
  std::string speciesFile;      // empty: the embedded config/species.json
  int clusterSize = 8;          // C of §3.4, 1 … 32
  int64_t maxPlants = 5000000;  // refuse boxes that grow more
  int64_t maxTrees = 1000000;   // refuse boxes that hold more trees
};

CLI::App* addPlantsCommand(CLI::App& cli, PlantsOptions& options);

// Exit code: 0 done; 2 a user mistake (bad --bbox / --format / --cluster-size / --max-plants /
// --max-trees, a box outside the dataset, a dataset without imagery, more plants than
// --max-plants or trees than --max-trees, a bad
// species file, an unwritable --output: one message naming it, nothing written); 1 an I/O failure.
int runPlants(const PlantsOptions& options, const Logger& log);

}  // namespace vegstream::app
