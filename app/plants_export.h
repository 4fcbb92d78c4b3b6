#pragma once
// `vegstream plants --format gpkg|geojson|csv` (app/plants_command.h): the plants and the trees
// of a box as two point tables written through GDAL/OGR (app/ogr_tables.h), and which files
// they go to.
//
// Tables (the same values as the JSON, digits of app/plants_fields.h):
//   plants  height_m, species, plant_height_m, stiffness, s_prime
//   trees   height_m, species, tree_height_m, crown_m, s_prime
// each row a 2D point at the root / foot of the trunk (WGS 84 lon, lat; CSV: "lon", "lat"
// columns). height_m is the ground there in metres above the dataset's vertical datum (that of
// its DEM, not the WGS 84 ellipsoid), so it is a field, not a Z coordinate (RFC 7946 reads a
// third coordinate as height above the ellipsoid).
//
// Files (--layer L picks one table; without it both are written):
//   gpkg             --output F: one GeoPackage, layers "plants" and "trees" (or layer L only).
//                    Without --output: a user error (a GeoPackage is not a stream).
//   geojson, csv     one table a file. --layer L: table L to --output F, or to standard output.
//                    No --layer: --output F is required and names two files, F's stem with
//                    "-plants" and "-trees" before its extension (box.csv → box-plants.csv,
//                    box-trees.csv), written together: both or neither.

#include <optional>
#include <string>
#include <vector>

#include "app/ogr_tables.h"
#include "core/result.h"
#include "scene/plants_in_box.h"
#include "scene/trees_in_box.h"
#include "vegetation/species_catalog.h"

namespace vegstream::app {

// A file of an export: its path ("" = standard output) and the tables ("plants", "trees") it holds.
struct ExportFile {
  std::string path;
  std::vector<std::string> tables;
};

// "gpkg", "geojson", "csv" → the format; nullopt for any other text (json is not an OGR export).
std::optional<TableFormat> parseExportFormat(const std::string& text);

// The files of an export by the rules above. layer: "", "plants" or "trees" (checked by the
// caller); output: "" for standard output. Errors: InvalidInput naming --output (and --format /
// --layer) when the combination cannot be written.
Result<std::vector<ExportFile>> exportFiles(TableFormat format, const std::string& formatName,
                                            const std::string& layer, const std::string& output);

struct PlantsExport {
  const std::vector<scene::BoxPlant>* plants = nullptr;
  const std::vector<scene::BoxTree>* trees = nullptr;
  const vegetation::SpeciesCatalog* catalog = nullptr;
  std::string dataset;   // its name, for the GeoPackage layers' descriptions
  std::string bboxText;  // "lon0, lat0, lon1, lat1"
};

// Writes the files (all or none). Errors: Io from GDAL naming the file.
Status writePlantsExport(TableFormat format, const std::vector<ExportFile>& files, const PlantsExport& data);

}  // namespace vegstream::app
