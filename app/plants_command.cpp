// `vegstream plants` (plants_command.h): checks every option, asks scene::treesInBox (every
// tree placed in the box, scene/trees_in_box.h) and scene::plantsInBox (every plant the full
// density grows there, scene/plants_in_box.h), and writes the tables: JSON here
// (app/plants_json.h), GeoPackage / GeoJSON / CSV through OGR (app/plants_export.h).

#include "app/plants_command.h"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <unistd.h>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/exit_codes.h"
#include "app/plants_export.h"
#include "app/plants_fields.h"
#include "app/plants_json.h"
#include "core/atomic_file.h"
#include "scene/plants_in_box.h"
#include "scene/trees_in_box.h"
#include "vegetation/plant_seeding.h"
#include "vegetation/species_catalog.h"

namespace vegstream::app {
namespace {

namespace fs = std::filesystem;

Error userError(std::string message) { return makeError(ErrorKind::InvalidInput, std::move(message)); }

Result<geo::GeoBounds> parseBbox(const std::string& text) {
  const std::string prefix = "--bbox " + text + ": ";
  double v[4];
  size_t start = 0;
  for (int i = 0; i < 4; ++i) {
    const size_t end = i < 3 ? text.find(',', start) : text.size();
    if (end == std::string::npos) return userError(prefix + "expected lon0,lat0,lon1,lat1 (four numbers, degrees)");
    const char* first = text.data() + start;
    const char* last = text.data() + end;
    const auto [ptr, ec] = std::from_chars(first, last, v[i]);
    if (ec != std::errc() || ptr != last || !std::isfinite(v[i]))
      return userError(prefix + "expected lon0,lat0,lon1,lat1 (four numbers, degrees); '" + std::string(first, last) +
                       "' is not a number");
    start = end + 1;
  }
  const geo::GeoBounds b{v[0], v[1], v[2], v[3]};
  if (b.westDeg < -180.0 || b.eastDeg > 180.0 || b.southDeg < -85.05 || b.northDeg > 85.05)
    return userError(prefix + "longitudes must be in -180 … 180 and latitudes in -85.05 … 85.05");
  if (b.westDeg >= b.eastDeg) return userError(prefix + "lon0 must be less than lon1");
  if (b.southDeg >= b.northDeg) return userError(prefix + "lat0 must be less than lat1");
  return b;
}

// A file the output will be (--output itself, or one it names): its directory must exist and
// be writable, and it must not be a directory. Errors name --output (and the file, if another).
Status checkOutputFile(const std::string& file, const std::string& output) {
  const std::string name = "--output " + output + ": " + (file == output ? "" : file + " ");
  const fs::path p(file);
  std::error_code ec;
  if (fs::is_directory(p, ec)) return userError(name + "is a directory");
  const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  if (!fs::is_directory(dir, ec)) return userError(name + "directory " + dir.string() + " does not exist");
  if (::access(dir.c_str(), W_OK) != 0) return userError(name + "directory " + dir.string() + " is not writable");
  return {};
}

// What will be written: JSON (no table format) to --output or stdout, or the files of an OGR
// export. Checked before any dataset I/O.
struct OutputPlan {
  std::optional<TableFormat> tables;  // nullopt: JSON
  std::vector<ExportFile> files;      // a path "" is standard output
};

Result<OutputPlan> planOutput(const PlantsOptions& o) {
  const std::optional<TableFormat> tables = parseExportFormat(o.format);
  if (!tables && o.format != "json")
    return userError("--format " + o.format + ": expected csv, geojson, gpkg or json");
  if (!o.layer.empty() && o.layer != "plants" && o.layer != "trees")
    return userError("--layer " + o.layer + ": expected plants or trees");
  OutputPlan plan{tables, {}};
  if (!tables) {
    if (!o.layer.empty())
      return userError("--layer " + o.layer + ": --format json holds both tables; --layer is for csv, geojson and gpkg");
    plan.files = {{o.output, {}}};
  } else {
    auto files = exportFiles(*tables, o.format, o.layer, o.output);
    if (!files) return files.error();
    plan.files = std::move(*files);
  }
  for (const ExportFile& f : plan.files)
    if (!f.path.empty())
      if (Status s = checkOutputFile(f.path, o.output); !s) return s.error();
  return plan;
}

struct Grown {
  scene::TreesInBox trees;
  scene::PlantsInBox plants;
};

// The trees first: the plants thin under their crowns, as in a flight (vegetation/canopy_cells.h).
Result<Grown> grow(const PlantsOptions& o, const geo::GeoBounds& box, const vegetation::SpeciesCatalog& catalog,
                   const Logger& log) {
  const std::string boxName = "--bbox " + o.bbox;
  scene::TreesInBoxOptions treeOptions;
  treeOptions.maxTrees = static_cast<uint64_t>(o.maxTrees);
  treeOptions.boxName = boxName;
  treeOptions.maxTreesName = "--max-trees";
  auto trees = scene::treesInBox(o.dataset, box, catalog, treeOptions);
  if (!trees) return trees.error();
  scene::PlantsInBoxOptions options;
  options.clusterSize = static_cast<uint32_t>(o.clusterSize);
  options.maxPlants = static_cast<uint64_t>(o.maxPlants);
  options.boxName = boxName;
  options.maxPlantsName = "--max-plants";
  options.crowns = std::move(trees->crowns);
  auto grown = scene::plantsInBox(o.dataset, box, catalog, options);
  if (!grown) return grown.error();
  // Trees are placed on their own grid (scene/trees_in_box.h) and listed in their own table; the
  // plant seeding's rare tree-species plants are not listed as plants.
  std::erase_if(grown->plants, [&](const scene::BoxPlant& p) { return vegetation::isTree(catalog.species[p.species]); });
  log->debug("plants: {} seed triangles (level {}), {} skipped for nodata, {} plants; {} trees ({} cells of {:.2f} m)",
             grown->seedTriangles, grown->seedLevel, grown->nodataSkipped, grown->plants.size(), trees->trees.size(),
             trees->cells, trees->cellM);
  return Grown{std::move(*trees), std::move(*grown)};
}

int writeJson(const PlantsOptions& o, const Grown& g, const vegetation::SpeciesCatalog& catalog,
              const std::string& bboxText, const Logger& log) {
  auto write = [&](std::ostream& out) {
    writePlantsJson(out, g.plants.plants, g.trees.trees, catalog, g.plants.datasetName, bboxText, g.plants.seedLevel,
                    o.clusterSize);
  };
  if (o.output.empty()) {
    write(std::cout);
    std::cout.flush();
    return std::cout ? kExitOk : reportError(log, makeError(ErrorKind::Io, "stdout: write failed"));
  }
  std::ostringstream text;
  write(text);
  const Status s = writeTextAtomically(o.output, text.str());
  if (!s) return reportError(log, s.error());
  return kExitOk;
}

int writeTables(const PlantsOptions& o, const OutputPlan& plan, const Grown& g,
                const vegetation::SpeciesCatalog& catalog, const std::string& bboxText, const Logger& log) {
  const PlantsExport data{&g.plants.plants, &g.trees.trees, &catalog, g.plants.datasetName, bboxText};
  const Status s = writePlantsExport(*plan.tables, plan.files, data);
  if (s) return kExitOk;
  if (o.output.empty()) return reportError(log, s.error());  // standard output: an I/O failure
  return reportError(log, userError("--output " + o.output + ": " + s.error().message));
}

}  // namespace

CLI::App* addPlantsCommand(CLI::App& cli, PlantsOptions& o) {
  auto* cmd = cli.add_subcommand(
      "plants", "Every plant the full density grows in a lon/lat box, and every tree there, as GIS tables or JSON");
  cmd->add_option("dataset", o.dataset, "Dataset directory (with imagery: species come from its colour)")->required();
  cmd->add_option("--bbox", o.bbox, "lon0,lat0,lon1,lat1 (WGS 84 degrees)")->required();
  cmd->add_option("--format", o.format,
                  "csv, geojson (RFC 7946), gpkg (GeoPackage: layers plants and trees; needs --output) or json "
                  "(both tables in one document)")
      ->capture_default_str();
  cmd->add_option("--layer", o.layer,
                  "plants or trees: write only that table (not with json). csv and geojson hold one table a file: "
                  "without --layer, --output F.ext writes F-plants.ext and F-trees.ext");
  cmd->add_option("--output", o.output,
                  "File to write (atomically); default: stdout (json, or csv / geojson with --layer)");
  cmd->add_option("--species", o.speciesFile, "Species catalog JSON (default: the embedded config/species.json)");
  cmd->add_option("--cluster-size", o.clusterSize, "Plants per cluster C, 1 … 32")->capture_default_str();
  cmd->add_option("--max-plants", o.maxPlants, "Refuse a box that grows more plants")->capture_default_str();
  cmd->add_option("--max-trees", o.maxTrees, "Refuse a box that holds more trees")->capture_default_str();
  return cmd;
}

int runPlants(const PlantsOptions& o, const Logger& log) {
  // Every option first, before any dataset I/O.
  if (o.clusterSize < 1 || o.clusterSize > int(vegetation::kMaxClusterSize))
    return reportError(log, userError("--cluster-size " + std::to_string(o.clusterSize) + ": must be 1 … 32"));
  if (o.maxPlants < 1)
    return reportError(log, userError("--max-plants " + std::to_string(o.maxPlants) + ": must be ≥ 1"));
  if (o.maxTrees < 1)
    return reportError(log, userError("--max-trees " + std::to_string(o.maxTrees) + ": must be ≥ 1"));
  auto plan = planOutput(o);
  if (!plan) return reportError(log, plan.error());
  auto box = parseBbox(o.bbox);
  if (!box) return reportError(log, box.error());
  const Result<vegetation::SpeciesCatalog> loaded = vegetation::loadSpeciesCatalogOrDefault(o.speciesFile);
  if (!loaded) return reportError(log, loaded.error());
  const vegetation::SpeciesCatalog* catalog = &*loaded;
  auto grown = grow(o, *box, *catalog, log);
  if (!grown) return reportError(log, grown.error());
  const auto f = formatNumber;
  const std::string bboxText = f("%.10g", box->westDeg) + ", " + f("%.10g", box->southDeg) + ", " +
                               f("%.10g", box->eastDeg) + ", " + f("%.10g", box->northDeg);
  if (!plan->tables) return writeJson(o, *grown, *catalog, bboxText, log);
  return writeTables(o, *plan, *grown, *catalog, bboxText, log);
}

}  // namespace vegstream::app
