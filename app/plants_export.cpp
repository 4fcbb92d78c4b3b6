// `vegstream plants` as GeoPackage, GeoJSON or CSV (plants_export.h): the two tables and the
// file-naming rule.

#include "app/plants_export.h"

#include <charconv>
#include <filesystem>

#include "app/plants_fields.h"

namespace vegstream::app {
namespace {
namespace fs = std::filesystem;

// The double a printed field reads back as: what the JSON says, to its last digit.
double value(const std::string& printed) {
  double v = 0.0;
  std::from_chars(printed.data(), printed.data() + printed.size(), v);
  return v;
}

std::vector<TableColumn> columns(const char* size, const char* third, const char* fourth) {
  using T = TableColumn::Type;
  return {{"height_m", T::Real}, {"species", T::Text}, {size, T::Real}, {third, T::Real}, {fourth, T::Real}};
}

PointTable plantsTable(const PlantsExport& d) {
  PointTable t{"plants", "", columns("plant_height_m", "stiffness", "s_prime"), d.plants->size(), {}};
  t.row = [&d](size_t i, double& lon, double& lat, std::span<TableValue> v) {
    const scene::BoxPlant& p = (*d.plants)[i];
    const PlantFields f = fieldsOf(p);
    lon = value(f.lon);
    lat = value(f.lat);
    v[0] = value(f.height);
    v[1] = std::string_view(d.catalog->species[p.species].name);
    v[2] = value(f.plantHeight);
    v[3] = value(f.stiffness);
    v[4] = value(f.sPrime);
  };
  return t;
}

PointTable treesTable(const PlantsExport& d) {
  PointTable t{"trees", "", columns("tree_height_m", "crown_m", "s_prime"), d.trees->size(), {}};
  t.row = [&d](size_t i, double& lon, double& lat, std::span<TableValue> v) {
    const scene::BoxTree& tree = (*d.trees)[i];
    const TreeFields f = fieldsOf(tree);
    lon = value(f.lon);
    lat = value(f.lat);
    v[0] = value(f.height);
    v[1] = std::string_view(d.catalog->species[tree.species].name);
    v[2] = value(f.treeHeight);
    v[3] = value(f.crown);
    v[4] = value(f.sPrime);
  };
  return t;
}

// F's stem + "-" + table + F's extension, in F's directory.
std::string suffixed(const std::string& output, const std::string& table) {
  const fs::path p(output);
  fs::path name = p.stem();
  name += "-" + table;
  name += p.extension();
  return (p.parent_path() / name).string();
}

}  // namespace

std::optional<TableFormat> parseExportFormat(const std::string& text) {
  if (text == "gpkg") return TableFormat::GeoPackage;
  if (text == "geojson") return TableFormat::GeoJson;
  if (text == "csv") return TableFormat::Csv;
  return std::nullopt;
}

Result<std::vector<ExportFile>> exportFiles(TableFormat format, const std::string& formatName,
                                            const std::string& layer, const std::string& output) {
  const std::vector<std::string> both = {"plants", "trees"};
  if (format == TableFormat::GeoPackage) {
    if (output.empty())
      return makeError(ErrorKind::InvalidInput,
                       "--format gpkg: needs --output FILE.gpkg (a GeoPackage cannot go to standard output)");
    return std::vector<ExportFile>{{output, layer.empty() ? both : std::vector<std::string>{layer}}};
  }
  if (!layer.empty()) return std::vector<ExportFile>{{output, {layer}}};
  if (output.empty())
    return makeError(ErrorKind::InvalidInput,
                     "--format " + formatName + ": one table a file; on standard output pick it with --layer plants|"
                     "trees, or give --output FILE for both (FILE-plants, FILE-trees)");
  std::vector<ExportFile> files;
  for (const std::string& table : both) files.push_back({suffixed(output, table), {table}});
  return files;
}

Status writePlantsExport(TableFormat format, const std::vector<ExportFile>& files, const PlantsExport& data) {
  PointTable plants = plantsTable(data), trees = treesTable(data);
  plants.description = "Plants of the vegstream dataset '" + data.dataset + "' in the box " + data.bboxText +
                       " (WGS 84 lon/lat; height_m: the ground above the dataset's vertical datum)";
  trees.description = "Trees of the vegstream dataset '" + data.dataset + "' in the box " + data.bboxText +
                      " (WGS 84 lon/lat; height_m: the ground above the dataset's vertical datum)";
  std::vector<TableFile> out;
  for (const ExportFile& f : files) {
    TableFile t{f.path.empty() ? fs::path("/vsistdout/") : fs::path(f.path), {}};
    for (const std::string& name : f.tables) t.tables.push_back(name == "plants" ? &plants : &trees);
    out.push_back(std::move(t));
  }
  return writeTableFiles(format, out);
}

}  // namespace vegstream::app
