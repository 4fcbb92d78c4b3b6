// `vegstream plants` (plants_command.h): parses the options, asks scene::plantsInBox (every
// plant the full density grows in the box, scene/plants_in_box.h) and scene::treesInBox (every
// tree placed there, scene/trees_in_box.h) and prints the rows.

#include "app/plants_command.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <unistd.h>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "app/exit_codes.h"
#include "core/atomic_file.h"
#include "scene/plants_in_box.h"
#include "scene/trees_in_box.h"
#include "vegetation/plant_seeding.h"
#include "vegetation/species_catalog.h"

namespace vegstream::app {
namespace {

namespace fs = std::filesystem;

Error userError(std::string message) { return makeError(ErrorKind::InvalidInput, std::move(message)); }

std::string fmt(const char* format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), format, v);
  return buf;
}

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

Status checkOutput(const std::string& output) {
  if (output.empty()) return {};
  const fs::path p(output);
  std::error_code ec;
  if (fs::is_directory(p, ec)) return userError("--output " + output + ": is a directory");
  const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  if (!fs::is_directory(dir, ec))
    return userError("--output " + output + ": directory " + dir.string() + " does not exist");
  if (::access(dir.c_str(), W_OK) != 0)
    return userError("--output " + output + ": directory " + dir.string() + " is not writable");
  return {};
}

// One writer for both formats, so CSV and JSON print the same digits.
struct Fields {
  std::string lat, lon, height, plantHeight, stiffness, sPrime;
};
Fields fieldsOf(const scene::BoxPlant& r) {
  return {fmt("%.10f", r.at.latDeg),      fmt("%.10f", r.at.lonDeg),        fmt("%.3f", r.at.heightM),
          fmt("%.4f", double(r.heightM)), fmt("%.5f", double(r.stiffness)), fmt("%.5f", double(r.sPrime))};
}

struct TreeFields {
  std::string lat, lon, height, treeHeight, crown, sPrime;
};
TreeFields fieldsOf(const scene::BoxTree& t) {
  return {fmt("%.10f", t.at.latDeg),      fmt("%.10f", t.at.lonDeg),       fmt("%.3f", t.at.heightM),
          fmt("%.3f", double(t.heightM)), fmt("%.3f", double(t.crownM)), fmt("%.5f", double(t.sPrime))};
}

// The plants' table, then a blank line and the trees' table (its own header).
void writeCsv(std::ostream& out, const std::vector<scene::BoxPlant>& rows, const std::vector<scene::BoxTree>& trees,
              const vegetation::SpeciesCatalog& catalog) {
  out << "lat,lon,height_m,species,plant_height_m,stiffness,s_prime\n";
  for (const scene::BoxPlant& r : rows) {
    const Fields f = fieldsOf(r);
    out << f.lat << ',' << f.lon << ',' << f.height << ',' << catalog.species[r.species].name << ',' << f.plantHeight
        << ',' << f.stiffness << ',' << f.sPrime << '\n';
  }
  out << "\nlat,lon,height_m,species,tree_height_m,crown_m,s_prime\n";
  for (const scene::BoxTree& t : trees) {
    const TreeFields f = fieldsOf(t);
    out << f.lat << ',' << f.lon << ',' << f.height << ',' << catalog.species[t.species].name << ',' << f.treeHeight
        << ',' << f.crown << ',' << f.sPrime << '\n';
  }
}

void writeJson(std::ostream& out, const std::vector<scene::BoxPlant>& rows, const std::vector<scene::BoxTree>& trees,
               const vegetation::SpeciesCatalog& catalog, const std::string& dataset, const std::string& bboxText,
               int seedLevel, int clusterSize) {
  // Written by hand, one plant per line: nlohmann would print the doubles with 17 digits.
  std::vector<std::string> names;
  for (const vegetation::Species& s : catalog.species) names.push_back(nlohmann::json(s.name).dump());
  out << "{\"dataset\": " << nlohmann::json(dataset).dump() << ",\n \"bbox\": [" << bboxText
      << "],\n \"seed_level\": " << seedLevel << ",\n \"cluster_size\": " << clusterSize
      << ",\n \"plant_count\": " << rows.size() << ",\n \"plants\": [";
  for (size_t i = 0; i < rows.size(); ++i) {
    const Fields f = fieldsOf(rows[i]);
    out << (i ? ",\n  " : "\n  ") << "{\"lat\": " << f.lat << ", \"lon\": " << f.lon << ", \"height_m\": " << f.height
        << ", \"species\": " << names[rows[i].species] << ", \"plant_height_m\": " << f.plantHeight
        << ", \"stiffness\": " << f.stiffness << ", \"s_prime\": " << f.sPrime << "}";
  }
  out << (rows.empty() ? "]" : "\n ]") << ",\n \"tree_count\": " << trees.size() << ",\n \"trees\": [";
  for (size_t i = 0; i < trees.size(); ++i) {
    const TreeFields f = fieldsOf(trees[i]);
    out << (i ? ",\n  " : "\n  ") << "{\"lat\": " << f.lat << ", \"lon\": " << f.lon << ", \"height_m\": " << f.height
        << ", \"species\": " << names[trees[i].species] << ", \"tree_height_m\": " << f.treeHeight
        << ", \"crown_m\": " << f.crown << ", \"s_prime\": " << f.sPrime << "}";
  }
  out << (trees.empty() ? "]}\n" : "\n ]}\n");
}

}  // namespace

CLI::App* addPlantsCommand(CLI::App& cli, PlantsOptions& o) {
  auto* cmd = cli.add_subcommand("plants", "Every plant the full density grows in a lon/lat box, as CSV or JSON");
  cmd->add_option("dataset", o.dataset, "Dataset directory (with imagery: species come from its colour)")->required();
  cmd->add_option("--bbox", o.bbox, "lon0,lat0,lon1,lat1 (WGS 84 degrees)")->required();
  cmd->add_option("--format", o.format, "csv or json")->capture_default_str();
  cmd->add_option("--output", o.output, "File to write (atomically); default: stdout");
  cmd->add_option("--species", o.speciesFile, "Species catalog JSON (default: the embedded config/species.json)");
  cmd->add_option("--cluster-size", o.clusterSize, "Plants per cluster C, 1 … 32")->capture_default_str();
  cmd->add_option("--max-plants", o.maxPlants, "Refuse a box that grows more plants")->capture_default_str();
  cmd->add_option("--max-trees", o.maxTrees, "Refuse a box that holds more trees")->capture_default_str();
  return cmd;
}

int runPlants(const PlantsOptions& o, const Logger& log) {
  // Every option first, before any dataset I/O.
  if (o.format != "csv" && o.format != "json")
    return reportError(log, userError("--format " + o.format + ": expected csv or json"));
  if (o.clusterSize < 1 || o.clusterSize > int(vegetation::kMaxClusterSize))
    return reportError(log, userError("--cluster-size " + std::to_string(o.clusterSize) + ": must be 1 … 32"));
  if (o.maxPlants < 1)
    return reportError(log, userError("--max-plants " + std::to_string(o.maxPlants) + ": must be ≥ 1"));
  if (o.maxTrees < 1)
    return reportError(log, userError("--max-trees " + std::to_string(o.maxTrees) + ": must be ≥ 1"));
  auto box = parseBbox(o.bbox);
  if (!box) return reportError(log, box.error());
  const vegetation::SpeciesCatalog* catalog = &vegetation::defaultSpeciesCatalog();
  Result<vegetation::SpeciesCatalog> custom = vegetation::SpeciesCatalog{};
  if (!o.speciesFile.empty()) {
    custom = vegetation::loadSpeciesCatalog(o.speciesFile);
    if (!custom) return reportError(log, custom.error());
    catalog = &*custom;
  }
  if (Status s = checkOutput(o.output); !s) return reportError(log, s.error());

  const std::string boxName = "--bbox " + o.bbox;
  // The trees first: the plants thin under their crowns, as in a flight (vegetation/canopy_cells.h).
  scene::TreesInBoxOptions treeOptions;
  treeOptions.maxTrees = static_cast<uint64_t>(o.maxTrees);
  treeOptions.boxName = boxName;
  treeOptions.maxTreesName = "--max-trees";
  auto trees = scene::treesInBox(o.dataset, *box, *catalog, treeOptions);
  if (!trees) return reportError(log, trees.error());
  scene::PlantsInBoxOptions options;
  options.clusterSize = static_cast<uint32_t>(o.clusterSize);
  options.maxPlants = static_cast<uint64_t>(o.maxPlants);
  options.boxName = boxName;
  options.maxPlantsName = "--max-plants";
  options.crowns = std::move(trees->crowns);
  auto grown = scene::plantsInBox(o.dataset, *box, *catalog, options);
  if (!grown) return reportError(log, grown.error());
  // Trees are placed on their own grid (scene/trees_in_box.h) and listed in their own table; the
  // plant seeding's rare tree-species plants are not listed as plants.
  std::erase_if(grown->plants, [&](const scene::BoxPlant& p) { return vegetation::isTree(catalog->species[p.species]); });
  log->debug("plants: {} seed triangles (level {}), {} skipped for nodata, {} plants; {} trees ({} cells of {:.2f} m)",
             grown->seedTriangles, grown->seedLevel, grown->nodataSkipped, grown->plants.size(), trees->trees.size(),
             trees->cells, trees->cellM);

  const std::string bboxText = fmt("%.10g", box->westDeg) + ", " + fmt("%.10g", box->southDeg) + ", " +
                               fmt("%.10g", box->eastDeg) + ", " + fmt("%.10g", box->northDeg);
  auto write = [&](std::ostream& out) {
    if (o.format == "csv")
      writeCsv(out, grown->plants, trees->trees, *catalog);
    else
      writeJson(out, grown->plants, trees->trees, *catalog, grown->datasetName, bboxText, grown->seedLevel,
                o.clusterSize);
  };
  if (o.output.empty()) {
    write(std::cout);
    std::cout.flush();
    return std::cout ? kExitOk : reportError(log, makeError(ErrorKind::Io, "stdout: write failed"));
  }
  const Status s = writeFileAtomically(o.output, [&](const fs::path& tmp) -> Status {
    std::ofstream f(tmp, std::ios::binary);
    write(f);
    f.close();
    if (!f) return makeError(ErrorKind::Io, "write failed");
    return {};
  });
  if (!s) return reportError(log, userError("--output " + o.output + ": " + s.error().message));
  return kExitOk;
}

}  // namespace vegstream::app
