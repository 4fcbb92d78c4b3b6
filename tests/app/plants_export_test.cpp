// `vegstream plants --format gpkg|geojson|csv` (app/plants_export.h) through the real executable,
// read back with GDAL/OGR: the layers' names, EPSG:4326 points inside the box, and every
// feature's position and fields equal to the JSON output's plant or tree, in order; GeoJSON per
// RFC 7946 and CSV as one table a file (header + one line a row); standard output equal to the
// file; the options' mistakes one line, exit 2, nothing written. In process (app/ogr_tables.h):
// a file that fails takes every file of the call with it and leaves an older file as it was.

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <memory>
#include <set>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <ogrsf_frmts.h>

#include "app/ogr_tables.h"
#include "tests/app/plants_fixture.h"

namespace vegstream::testing {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;

struct CloseDataset {
  void operator()(GDALDataset* d) const { GDALClose(d); }
};
using Dataset = std::unique_ptr<GDALDataset, CloseDataset>;

// A vector file opened read-only by one driver; null if it does not open.
Dataset openVector(const fs::path& p, const char* driver, std::vector<const char*> openOptions = {}) {
  static const bool registered = (GDALAllRegister(), true);
  (void)registered;
  const char* drivers[] = {driver, nullptr};
  openOptions.push_back(nullptr);
  return Dataset(GDALDataset::Open(p.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, drivers, openOptions.data()));
}

std::vector<std::string> names(const fs::path& dir) {
  std::vector<std::string> n;
  for (const auto& e : fs::directory_iterator(dir)) n.push_back(e.path().filename().string());
  std::sort(n.begin(), n.end());
  return n;
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

const std::vector<std::string> kPlantColumns = {"height_m", "species", "plant_height_m", "stiffness", "s_prime"};
const std::vector<std::string> kTreeColumns = {"height_m", "species", "tree_height_m", "crown_m", "s_prime"};

// Every feature of `layer`, in order, is the JSON's row: the point at (lon, lat) exactly, inside
// the half-open box, and each column's value (reals to the last bit: the digits the JSON prints).
void expectLayerIsJson(OGRLayer& layer, const json& rows, const std::vector<std::string>& columns,
                       const std::vector<double>& box) {
  SCOPED_TRACE(layer.GetName());
  ASSERT_EQ(layer.GetFeatureCount(), GIntBig(rows.size()));
  layer.ResetReading();
  size_t i = 0;
  for (const auto& f : layer) {
    ASSERT_LT(i, rows.size());
    const json& r = rows[i];
    const OGRGeometry* g = f->GetGeometryRef();
    ASSERT_NE(g, nullptr) << "feature " << i;
    ASSERT_EQ(wkbFlatten(g->getGeometryType()), wkbPoint);
    const double lon = g->toPoint()->getX(), lat = g->toPoint()->getY();
    ASSERT_EQ(lon, r["lon"].get<double>()) << "feature " << i;
    ASSERT_EQ(lat, r["lat"].get<double>()) << "feature " << i;
    ASSERT_TRUE(lon >= box[0] && lon < box[2] && lat >= box[1] && lat < box[3]) << lon << " " << lat;
    for (const std::string& c : columns) {
      if (c == "species")
        ASSERT_EQ(std::string(f->GetFieldAsString(c.c_str())), r[c].get<std::string>()) << "feature " << i;
      else
        ASSERT_EQ(f->GetFieldAsDouble(c.c_str()), r[c].get<double>()) << c << " of feature " << i;
    }
    ++i;
  }
  EXPECT_EQ(i, rows.size());
}

class PlantsExport : public Plants {
 protected:
  // The JSON of the box: 30 m × 30 m at the centre, grass and a few conifers.
  void SetUp() override {
    Plants::SetUp();
    if (HasFatalFailure()) return;
    box_ = bbox(15.0);
    const auto j = runVegstream(plants("--bbox " + box_ + " --format json"));
    ASSERT_EQ(j.exitCode, 0) << j.err;
    doc_ = json::parse(j.out);
    ASSERT_GT(doc_["plants"].size(), 5000u);
    ASSERT_GT(doc_["trees"].size(), 5u) << "the box must hold trees for the trees' layer to say anything";
    out_ = testTmp("export");
    fs::create_directories(out_);
  }
  // Runs `plants --bbox box_ ARGS` and expects it to succeed silently on stderr.
  CommandResult run(const std::string& args) const {
    auto r = runVegstream(plants("--bbox " + box_ + " " + args));
    EXPECT_EQ(r.exitCode, 0) << args << "\n" << r.err;
    EXPECT_EQ(r.err, "") << args;
    return r;
  }
  std::string box_;
  json doc_;
  fs::path out_;
};

TEST_F(PlantsExport, GeoPackageHoldsPlantsAndTreesLayersEqualToTheJson) {
  const auto r = run("--format gpkg --output " + q(out_ / "box.gpkg"));
  EXPECT_EQ(r.out, "");
  const Dataset ds = openVector(out_ / "box.gpkg", "GPKG");
  ASSERT_TRUE(ds) << CPLGetLastErrorMsg();
  ASSERT_EQ(ds->GetLayerCount(), 2);
  OGRLayer* plantsLayer = ds->GetLayerByName("plants");
  OGRLayer* treesLayer = ds->GetLayerByName("trees");
  ASSERT_NE(plantsLayer, nullptr);
  ASSERT_NE(treesLayer, nullptr);
  for (OGRLayer* l : {plantsLayer, treesLayer}) {
    ASSERT_NE(l->GetSpatialRef(), nullptr);
    EXPECT_STREQ(l->GetSpatialRef()->GetAuthorityCode(nullptr), "4326");
    EXPECT_EQ(wkbFlatten(l->GetGeomType()), wkbPoint);
    EXPECT_NE(std::string(l->GetMetadataItem("DESCRIPTION")).find("'synth'"), std::string::npos);
  }
  const std::vector<double> box = numbers(box_);
  expectLayerIsJson(*plantsLayer, doc_["plants"], kPlantColumns, box);
  expectLayerIsJson(*treesLayer, doc_["trees"], kTreeColumns, box);
  // --layer: that table only.
  run("--format gpkg --layer trees --output " + q(out_ / "trees.gpkg"));
  const Dataset trees = openVector(out_ / "trees.gpkg", "GPKG");
  ASSERT_TRUE(trees);
  ASSERT_EQ(trees->GetLayerCount(), 1);
  expectLayerIsJson(*trees->GetLayer(0), doc_["trees"], kTreeColumns, box);
  EXPECT_EQ(names(out_), (std::vector<std::string>{"box.gpkg", "trees.gpkg"})) << "no temporary, no journal";
}

TEST_F(PlantsExport, GeoJsonIsRfc7946WithOneTableAFile) {
  run("--format geojson --output " + q(out_ / "b.geojson"));
  EXPECT_EQ(names(out_), (std::vector<std::string>{"b-plants.geojson", "b-trees.geojson"}));
  const std::vector<double> box = numbers(box_);
  for (const auto& [table, columns] : {std::pair{std::string("plants"), kPlantColumns}, {"trees", kTreeColumns}}) {
    SCOPED_TRACE(table);
    const fs::path file = out_ / ("b-" + table + ".geojson");
    // RFC 7946 as text: a FeatureCollection without "crs", [lon, lat] positions.
    const json fc = json::parse(readWhole(file));
    EXPECT_EQ(fc["type"], "FeatureCollection");
    EXPECT_FALSE(fc.contains("crs"));
    ASSERT_EQ(fc["features"].size(), doc_[table].size());
    const json& first = fc["features"][0];
    EXPECT_EQ(first["geometry"]["coordinates"], json::array({doc_[table][0]["lon"], doc_[table][0]["lat"]}));
    std::set<std::string> keys;
    for (const auto& [k, v] : first["properties"].items()) keys.insert(k);
    EXPECT_EQ(keys, std::set<std::string>(columns.begin(), columns.end()));
    // And through GDAL: one layer, every feature the JSON's.
    const Dataset ds = openVector(file, "GeoJSON");
    ASSERT_TRUE(ds) << CPLGetLastErrorMsg();
    ASSERT_EQ(ds->GetLayerCount(), 1);
    expectLayerIsJson(*ds->GetLayer(0), doc_[table], columns, box);
  }
  // --layer to standard output: the same bytes as the file.
  const auto s = run("--format geojson --layer trees");
  EXPECT_EQ(s.out, readWhole(out_ / "b-trees.geojson"));
}

TEST_F(PlantsExport, CsvIsOneTableAFileThatGdalAndAPlainReaderRead) {
  run("--format csv --output " + q(out_ / "box.csv"));
  EXPECT_EQ(names(out_), (std::vector<std::string>{"box-plants.csv", "box-trees.csv"}));
  const std::vector<double> box = numbers(box_);
  for (const auto& [table, columns] : {std::pair{std::string("plants"), kPlantColumns}, {"trees", kTreeColumns}}) {
    SCOPED_TRACE(table);
    const fs::path file = out_ / ("box-" + table + ".csv");
    // One table: a header and one line a row, every line seven cells, no empty line.
    const std::vector<std::string> l = lines(readWhole(file));
    ASSERT_EQ(l.size(), doc_[table].size() + 1);
    std::string header = "lon,lat";
    for (const std::string& c : columns) header += "," + c;
    EXPECT_EQ(l[0], header);
    for (const std::string& row : l) ASSERT_EQ(std::count(row.begin(), row.end(), ','), 6) << row;
    // GDAL's CSV driver with lon/lat found by name: points, and every row the JSON's.
    const Dataset ds = openVector(file, "CSV", {"X_POSSIBLE_NAMES=lon", "Y_POSSIBLE_NAMES=lat"});
    ASSERT_TRUE(ds) << CPLGetLastErrorMsg();
    ASSERT_EQ(ds->GetLayerCount(), 1);
    expectLayerIsJson(*ds->GetLayer(0), doc_[table], columns, box);
  }
  const auto s = run("--layer plants");  // csv is the default format
  EXPECT_EQ(s.out, readWhole(out_ / "box-plants.csv"));
}

TEST_F(PlantsExport, AnEmptyTableKeepsItsHeaderAndLayer) {
  // One grass species: plants, no trees.
  std::ofstream(out_ / "moss.json") << R"({"species": [{"name": "moss", "reference": {"srgb": "#406030"},
    "weights": {"h": 1, "s": 1, "v": 1}, "p": 2, "kind": "grass", "height_m": {"min": 0.01, "max": 0.02},
    "stiffness": {"min": 0.8, "max": 0.9}, "width_m": {"min": 0.001, "max": 0.002},
    "colour_modulation": {"min": 1, "max": 1}}]})";
  const std::string species = "--species " + q(out_ / "moss.json") + " ";
  EXPECT_EQ(run(species + "--layer trees").out, "lon,lat,height_m,species,tree_height_m,crown_m,s_prime\n");
  const json fc = json::parse(run(species + "--format geojson --layer trees").out);
  EXPECT_EQ(fc["type"], "FeatureCollection");
  EXPECT_TRUE(fc["features"].empty());
  run(species + "--format gpkg --output " + q(out_ / "m.gpkg"));
  const Dataset ds = openVector(out_ / "m.gpkg", "GPKG");
  ASSERT_TRUE(ds);
  ASSERT_NE(ds->GetLayerByName("trees"), nullptr);
  EXPECT_EQ(ds->GetLayerByName("trees")->GetFeatureCount(), 0);
  EXPECT_GT(ds->GetLayerByName("plants")->GetFeatureCount(), 3000);
}

TEST_F(PlantsExport, MistakesAreOneLineExitTwoAndWriteNothing) {
  fs::create_directories(out_ / "taken-trees.csv");  // a directory where a file would go
  const std::string b = "--bbox " + box_ + " ";
  struct Case {
    std::string args, names;
  };
  const std::vector<Case> cases = {
      {b + "--format gpkg", "--format gpkg"},
      {b + "--format gpkg --layer plants", "--output"},
      {b + "--format gpkg --layer bushes --output " + q(out_ / "x.gpkg"), "--layer bushes"},
      {b + "--format json --layer trees --output " + q(out_ / "x.json"), "--layer trees"},
      {b + "--format csv", "--layer"},
      {b + "--format geojson", "--layer"},
      {b + "--format shp --output " + q(out_ / "x.shp"), "--format shp"},
      {b + "--format gpkg --output " + q(out_ / "missing" / "x.gpkg"), "--output"},
      {b + "--format csv --output " + q(out_ / "missing" / "x.csv"), "--output"},
      {b + "--format geojson --layer trees --output " + q(out_ / "missing" / "x.geojson"), "--output"},
      {b + "--format csv --output " + q(out_ / "taken.csv"), "taken-trees.csv"},
  };
  for (const Case& c : cases) {
    const auto r = runVegstream(plants(c.args));
    EXPECT_EQ(r.exitCode, 2) << c.args << "\n" << r.err;
    EXPECT_EQ(countLines(r.err), 1) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.names), std::string::npos) << c.args << "\n" << r.err;
    EXPECT_TRUE(r.out.empty()) << c.args;
    EXPECT_EQ(names(out_), std::vector<std::string>{"taken-trees.csv"}) << c.args;
  }
}

// Three points of a table named `name` (in process, no dataset).
vegstream::app::PointTable smallTable(const std::string& name) {
  vegstream::app::PointTable t;
  t.name = name;
  t.columns = {{"kind", vegstream::app::TableColumn::Type::Text}, {"size_m", vegstream::app::TableColumn::Type::Real}};
  t.rowCount = 3;
  t.row = [](size_t i, double& lon, double& lat, std::span<vegstream::app::TableValue> v) {
    lon = 7.0 + 0.001 * double(i);
    lat = 46.0;
    v[0] = std::string_view(i % 2 ? "odd" : "even");
    v[1] = 0.5 * double(i);
  };
  return t;
}

TEST(OgrTables, AFailingFileTakesTheWholeCallWithItAndLeavesOlderFilesAsTheyWere) {
  using vegstream::app::TableFile;
  using vegstream::app::TableFormat;
  const fs::path dir = testTmp("ogr_tables");
  fs::create_directories(dir);
  std::ofstream(dir / "a.gpkg") << "older";
  const auto t = smallTable("t");
  // b.gpkg asks for the layer "t" twice: GDAL refuses the second, after a.gpkg is complete.
  const std::vector<TableFile> failing = {{dir / "a.gpkg", {&t}}, {dir / "b.gpkg", {&t, &t}}};
  const Status s = vegstream::app::writeTableFiles(TableFormat::GeoPackage, failing);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("b.gpkg"), std::string::npos) << s.error().message;
  EXPECT_EQ(names(dir), std::vector<std::string>{"a.gpkg"}) << "no b.gpkg, no temporary, no journal";
  EXPECT_EQ(readWhole(dir / "a.gpkg"), "older");
  // The same without the mistake: a.gpkg replaced by a GeoPackage of three points.
  const std::vector<TableFile> good = {{dir / "a.gpkg", {&t}}};
  ASSERT_TRUE(vegstream::app::writeTableFiles(TableFormat::GeoPackage, good).ok());
  const Dataset ds = openVector(dir / "a.gpkg", "GPKG");
  ASSERT_TRUE(ds);
  EXPECT_EQ(ds->GetLayer(0)->GetFeatureCount(), 3);
  EXPECT_EQ(names(dir), std::vector<std::string>{"a.gpkg"});
  // Shapes no format holds: two tables in one CSV, a GeoPackage on standard output.
  const std::vector<TableFile> twoInCsv = {{dir / "c.csv", {&t, &t}}};
  EXPECT_EQ(vegstream::app::writeTableFiles(TableFormat::Csv, twoInCsv).error().kind, ErrorKind::InvalidInput);
  const std::vector<TableFile> gpkgOut = {{"/vsistdout/", {&t}}};
  EXPECT_EQ(vegstream::app::writeTableFiles(TableFormat::GeoPackage, gpkgOut).error().kind, ErrorKind::InvalidInput);
  EXPECT_EQ(names(dir), std::vector<std::string>{"a.gpkg"});
  fs::remove_all(dir);
}

}  // namespace
}  // namespace vegstream::testing
