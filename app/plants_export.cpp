// `vegstream plants` as GeoPackage, GeoJSON or CSV (plants_export.h): the two tables and the
// file-naming rule.

#include "app/plants_export.h"

#include <array>
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

// The table `name` of `items` (plants or trees): position, height and species, then the three
// columns of their own that own(fieldsOf(item)) picks, each the double its printed field reads
// back as.
template <class Item, class Own>
PointTable pointTable(const char* name, std::vector<TableColumn> columns, const std::vector<Item>& items,
                      const vegetation::SpeciesCatalog& catalog, Own own) {
  PointTable t{name, "", std::move(columns), items.size(), {}};
  t.row = [&items, &catalog, own](size_t i, double& lon, double& lat, std::span<TableValue> v) {
    const Item& item = items[i];
    const auto f = fieldsOf(item);
    lon = value(f.lon);
    lat = value(f.lat);
    v[0] = value(f.height);
    v[1] = std::string_view(catalog.species[item.species].name);
    const std::array<const std::string*, 3> printed = own(f);
    for (size_t k = 0; k < printed.size(); ++k) v[2 + k] = value(*printed[k]);
  };
  return t;
}

PointTable plantsTable(const PlantsExport& d) {
  return pointTable("plants", columns("plant_height_m", "stiffness", "s_prime"), *d.plants, *d.catalog,
                    [](const PlantFields& f) {
                      return std::array{&f.plantHeight, &f.stiffness, &f.sPrime};
                    });
}

PointTable treesTable(const PlantsExport& d) {
  return pointTable("trees", columns("tree_height_m", "crown_m", "s_prime"), *d.trees, *d.catalog,
                    [](const TreeFields& f) {
                      return std::array{&f.treeHeight, &f.crown, &f.sPrime};
                    });
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

Result<std::vector<ExportFile>> exportFiles(TableFormat format, const std::string& formatName, const std::string& layer,
                                            const std::string& output) {
  const std::vector<std::string> both = {"plants", "trees"};
  if (format == TableFormat::GeoPackage) {
    if (output.empty())
      return makeError(ErrorKind::InvalidInput,
                       "--format gpkg: needs --output FILE.gpkg (a GeoPackage cannot go to standard output)");
    return std::vector<ExportFile>{{output, layer.empty() ? both : std::vector<std::string>{layer}}};
  }
  if (!layer.empty()) return std::vector<ExportFile>{{output, {layer}}};
  if (output.empty())
    return makeError(ErrorKind::InvalidInput, "--format " + formatName +
                                                  ": one table a file; on standard output pick it with --layer plants|"
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
