#pragma once
// `vegstream plants DATASET --bbox lon0,lat0,lon1,lat1 [--format csv|geojson|gpkg|json]
//  [--layer plants|trees] [--output FILE] [--species FILE] [--cluster-size C] [--max-plants N]
//  [--max-trees N]`: every plant the full density grows in a lon/lat box, and every tree placed
// there — the CPU reference of what a flight draws there (core seed
// ../shared/seeds/001_3eca9f2c7752e4fb.txt §2.2 seeding, §3.1 seed triangles, §3.3 species from
// the imagery colour, §3.4 clusters) — as tables GIS tools read, or as one JSON document.
//
// Full density: every seed triangle (terrain/seed_region.h) gets n_max = SeedOptions::maxPlants
// plants, i.e. what a camera close enough grows; a plant depends only on its triangle and index,
// so the output depends on the ground alone, never on a camera, and a box's plants are exactly
// the plants of any larger box that lie in it. A plant is in the box when
// lon0 ≤ lon < lon1 and lat0 ≤ lat < lat1 (half-open: adjacent boxes share none).
//
// Two tables, in the seed triangles' depth-first order and each triangle's sequence order for
// the plants, in the tree grid's row-major cell order for the trees (issue 20: every tree the
// view-independent tree placement puts there, scene/trees_in_box.h):
//   plants  lon, lat (WGS 84 degrees of the root), height_m (the ground there, m above the
//           dataset's datum), species (catalog name), plant_height_m (full-size height),
//           stiffness (k′), s_prime (eq. 18)
//   trees   lon, lat, height_m, species at the foot of the trunk, tree_height_m, crown_m, s_prime
// Tree species are listed only as trees (the plant seeding's rare plants of a tree species are
// left out of the plants). Digits: app/plants_fields.h, the same in every format.
//
// Formats (the files each writes: app/plants_export.h):
//   gpkg     a GeoPackage (--output required): layers "plants" and "trees", EPSG:4326 points
//   geojson  RFC 7946 FeatureCollections, one table a file
//   csv      one table a file: header, then one row a plant or tree, lon and lat first
//   json     both tables in one document (app/plants_json.h); --layer does not apply
// One table a file: with --layer L, table L goes to --output (or standard output); without it,
// --output F names two files, F's stem + "-plants" / "-trees" + F's extension.
// gpkg, geojson and csv are written through GDAL/OGR (app/ogr_tables.h).

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
  std::string format = "csv";   // csv | geojson | gpkg | json
  std::string layer;            // empty: both tables; plants | trees
  std::string output;           // empty: stdout
  std::string speciesFile;      // empty: the embedded config/species.json
  int clusterSize = 8;          // C of §3.4, 1 … 32
  int64_t maxPlants = 5000000;  // refuse boxes that grow more
  int64_t maxTrees = 1000000;   // refuse boxes that hold more trees
};

CLI::App* addPlantsCommand(CLI::App& cli, PlantsOptions& options);

// Exit code: 0 done; 2 a user mistake (bad --bbox / --format / --layer / --cluster-size /
// --max-plants / --max-trees, --layer with json, gpkg without --output, csv or geojson of both
// tables to standard output, a box outside the dataset, a dataset without imagery, more plants
// than --max-plants or trees than --max-trees, a bad species file, an unwritable --output: one
// message naming it, nothing written); 1 an I/O failure.
int runPlants(const PlantsOptions& options, const Logger& log);

}  // namespace vegstream::app
