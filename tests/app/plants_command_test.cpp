// `vegstream plants` (app/plants_command.h) on a small synthetic dataset, through the real
// executable: CSV (one table a file, --layer) and JSON agree (plants, and trees in their own
// table), every plant and tree is in the box, the output is deterministic, a sub-box gives
// exactly the big box's plants that lie in it (view and box independence, core seed
// ../shared/seeds/001_3eca9f2c7752e4fb.txt §2.2), species come from the catalog, and every user
// mistake is one message naming the option, exit 2 and no output file. The GIS formats read
// back through GDAL: plants_export_test.cpp.

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/app/plants_fixture.h"

namespace vegstream::testing {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;

struct Row {
  double lat = 0, lon = 0, height = 0, plantHeight = 0, stiffness = 0, sPrime = 0;
  std::string species;
  bool operator==(const Row&) const = default;
};

// `--format csv --layer plants`: a header, then one line a plant (lon, lat first).
std::vector<Row> parseCsv(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "lon,lat,height_m,species,plant_height_m,stiffness,s_prime");
  std::vector<Row> rows;
  while (std::getline(in, line)) {
    EXPECT_FALSE(line.empty()) << "one table: no empty line";
    std::vector<std::string> f;
    std::stringstream ls(line);
    for (std::string cell; std::getline(ls, cell, ',');) f.push_back(cell);
    EXPECT_EQ(f.size(), 7u) << line;
    if (f.size() != 7) break;
    rows.push_back(
        {std::stod(f[1]), std::stod(f[0]), std::stod(f[2]), std::stod(f[4]), std::stod(f[5]), std::stod(f[6]), f[3]});
  }
  return rows;
}

struct TreeRow {
  double lat = 0, lon = 0, height = 0, treeHeight = 0, crown = 0, sPrime = 0;
  std::string species;
  bool operator==(const TreeRow&) const = default;
};

// `--format csv --layer trees`: a header, then one line a tree (lon, lat first).
std::vector<TreeRow> parseTreesCsv(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "lon,lat,height_m,species,tree_height_m,crown_m,s_prime");
  std::vector<TreeRow> rows;
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream ls(line);
    for (std::string cell; std::getline(ls, cell, ',');) f.push_back(cell);
    EXPECT_EQ(f.size(), 7u) << line;
    if (f.size() != 7) break;
    rows.push_back(
        {std::stod(f[1]), std::stod(f[0]), std::stod(f[2]), std::stod(f[4]), std::stod(f[5]), std::stod(f[6]), f[3]});
  }
  return rows;
}

TEST_F(Plants, CsvAndJsonAgreeInsideTheBoxAndRunsAreIdentical) {
  const std::string box = bbox(15.0);
  const auto a = runVegstream(plants("--bbox " + box + " --layer plants"));
  ASSERT_EQ(a.exitCode, 0) << a.err;
  const auto b = runVegstream(plants("--bbox " + box + " --format csv --layer plants"));
  ASSERT_EQ(b.exitCode, 0) << b.err;
  EXPECT_EQ(a.out, b.out) << "byte-identical runs";
  const std::vector<Row> rows = parseCsv(a.out);
  // 900 m² at full density: each species' density_m2 (grass 400 per m², gravel 12), less bare soil.
  EXPECT_GT(rows.size(), 5000u);
  EXPECT_LT(rows.size(), 420000u);

  const fs::path out = testTmp("plants_json") / "p.json";
  fs::create_directories(out.parent_path());
  const auto j = runVegstream(plants("--bbox " + box + " --format json --output " + q(out)));
  ASSERT_EQ(j.exitCode, 0) << j.err;
  EXPECT_TRUE(j.out.empty());
  std::ifstream in(out);
  const json doc = json::parse(in);
  EXPECT_EQ(doc["dataset"], "synth");
  EXPECT_EQ(doc["cluster_size"], 8);
  EXPECT_GT(doc["seed_level"].get<int>(), 20);
  ASSERT_EQ(doc["plant_count"].get<size_t>(), rows.size());
  ASSERT_EQ(doc["plants"].size(), rows.size());
  const std::vector<double> v = numbers(box);
  ASSERT_EQ(doc["bbox"].size(), 4u);
  for (size_t k = 0; k < 4; ++k) EXPECT_NEAR(doc["bbox"][k].get<double>(), v[k], 1e-8);  // echoed at 8 decimals

  std::set<std::string> names;
  for (size_t i = 0; i < rows.size(); ++i) {
    const json& p = doc["plants"][i];
    const Row r{p["lat"], p["lon"], p["height_m"], p["plant_height_m"], p["stiffness"], p["s_prime"], p["species"]};
    ASSERT_EQ(r, rows[i]) << "row " << i;
    ASSERT_GE(r.lon, v[0]);
    ASSERT_LT(r.lon, v[2]);
    ASSERT_GE(r.lat, v[1]);
    ASSERT_LT(r.lat, v[3]);
    ASSERT_GT(r.plantHeight, 0.0);
    ASSERT_GT(r.stiffness, 0.0);
    ASSERT_GT(r.sPrime, 0.0);
    ASSERT_LE(r.sPrime, 1.0);
    names.insert(r.species);
  }
  // Names from the default catalog, never a bare entry.
  const std::set<std::string> growing = {"grass", "conifer", "red gravel", "dry tufts"};
  for (const std::string& n : names) EXPECT_TRUE(growing.count(n)) << n;
  EXPECT_GE(names.size(), 1u);
  fs::remove_all(out.parent_path());
}

TEST_F(Plants, ASubBoxGivesExactlyTheBigBoxsPlantsInIt) {
  const std::string big = bbox(15.0), small = bbox(10.0, 4.0);
  const auto a = runVegstream(plants("--bbox " + big + " --layer plants"));
  const auto b = runVegstream(plants("--bbox " + small + " --layer plants"));
  ASSERT_EQ(a.exitCode, 0) << a.err;
  ASSERT_EQ(b.exitCode, 0) << b.err;
  const std::vector<double> s = numbers(small);
  // Rows printed within 1e-9° of an edge of the small box could round across it: left out.
  const auto inSmall = [&](const Row& r) { return r.lon >= s[0] && r.lon < s[2] && r.lat >= s[1] && r.lat < s[3]; };
  const auto nearEdge = [&](const Row& r) {
    return std::abs(r.lon - s[0]) < 1e-9 || std::abs(r.lon - s[2]) < 1e-9 || std::abs(r.lat - s[1]) < 1e-9 ||
           std::abs(r.lat - s[3]) < 1e-9;
  };
  std::vector<Row> expected, got;
  for (const Row& r : parseCsv(a.out))
    if (inSmall(r) && !nearEdge(r)) expected.push_back(r);
  for (const Row& r : parseCsv(b.out))
    if (!nearEdge(r)) got.push_back(r);
  EXPECT_GT(expected.size(), 2000u);
  ASSERT_EQ(got.size(), expected.size());
  for (size_t i = 0; i < got.size(); ++i) ASSERT_EQ(got[i], expected[i]) << "row " << i;
}

TEST_F(Plants, SpeciesComeFromTheCatalogAndBareGroundGrowsNone) {
  const fs::path tmp = testTmp("plants_species");
  fs::create_directories(tmp);
  // One species: every plant is it. Only bare soil: nothing grows.
  std::ofstream(tmp / "moss.json") << R"({"species": [{"name": "moss", "reference": {"srgb": "#406030"},
    "weights": {"h": 1, "s": 1, "v": 1}, "p": 2, "kind": "grass", "height_m": {"min": 0.01, "max": 0.02},
    "stiffness": {"min": 0.8, "max": 0.9}, "width_m": {"min": 0.001, "max": 0.002},
    "colour_modulation": {"min": 1, "max": 1}}]})";
  std::ofstream(tmp / "bare.json") << R"({"species": [
    {"name": "dust", "reference": {"srgb": "#808080"}, "weights": {"h": 0, "s": 0, "v": 1}, "p": 2, "bare": true},
    {"name": "blue moss", "reference": {"srgb": "#0000ff"}, "weights": {"h": 1, "s": 1, "v": 1}, "p": 8,
     "threshold": 1e9, "kind": "grass", "height_m": {"min": 0.01, "max": 0.02}, "stiffness": {"min": 0.8, "max": 0.9},
     "width_m": {"min": 0.001, "max": 0.002}, "colour_modulation": {"min": 1, "max": 1}}]})";
  const std::string box = bbox(25.0);
  const auto moss = runVegstream(plants("--bbox " + box + " --layer plants --species " + q(tmp / "moss.json")));
  ASSERT_EQ(moss.exitCode, 0) << moss.err;
  const std::vector<Row> rows = parseCsv(moss.out);
  EXPECT_GT(rows.size(), 3000u);
  for (const Row& r : rows) {
    ASSERT_EQ(r.species, "moss");
    ASSERT_GE(r.plantHeight, 0.01 * 0.6 - 1e-4);
    ASSERT_LE(r.plantHeight, 0.02 + 1e-4);
  }
  const auto bare = runVegstream(plants("--bbox " + box + " --species " + q(tmp / "bare.json") + " --format json"));
  ASSERT_EQ(bare.exitCode, 0) << bare.err;
  const json j = json::parse(bare.out);
  EXPECT_EQ(j["plant_count"], 0);
  EXPECT_TRUE(j["plants"].empty());
  fs::remove_all(tmp);
}

// A catalog of one tree species on the synthetic dataset's dark green and bare everything else:
// no plants, so a box large enough for many trees stays cheap.
void writeTreeCatalog(const fs::path& file) {
  std::ofstream(file) << R"({"species": [
    {"name": "meadow", "reference": {"h_deg": 88, "s": 0.28, "v": 0.2}, "weights": {"h": 2, "s": 0.5, "v": 0.8},
     "p": 3, "bare": true},
    {"name": "rock", "reference": {"h_deg": 0, "s": 0.04, "v": 0.42}, "weights": {"h": 0, "s": 2, "v": 0.4}, "p": 3,
     "bare": true},
    {"name": "pine", "reference": {"h_deg": 104, "s": 0.4, "v": 0.1}, "weights": {"h": 2.5, "s": 0.5, "v": 1.0},
     "p": 3, "kind": "tree", "height_m": {"min": 8, "max": 22}, "stiffness": {"min": 5, "max": 12},
     "width_m": {"min": 3, "max": 7}, "colour_modulation": {"min": 1, "max": 1},
     "tree": {"form": "conifer", "density_ha": 180, "spacing_m": 3.5}}]})";
}

TEST_F(Plants, TreesAreListedInTheirOwnTableAlikeInCsvAndJsonAndASubBoxKeepsThem) {
  const fs::path tmp = testTmp("plants_trees");
  fs::create_directories(tmp);
  writeTreeCatalog(tmp / "trees.json");
  const std::string species = " --species " + q(tmp / "trees.json");
  const std::string big = bbox(400.0), small = bbox(250.0, 60.0);
  const auto a = runVegstream(plants("--bbox " + big + species + " --layer plants"));
  ASSERT_EQ(a.exitCode, 0) << a.err;
  EXPECT_TRUE(parseCsv(a.out).empty()) << "bare soil and trees only: no plants";
  const auto at = runVegstream(plants("--bbox " + big + species + " --layer trees"));
  ASSERT_EQ(at.exitCode, 0) << at.err;
  const std::vector<TreeRow> trees = parseTreesCsv(at.out);
  const std::vector<double> v = numbers(big);
  const double ha = 0.8 * 0.8 * 100.0;
  std::printf("[ figures  ] %zu trees in %.0f ha of the synthetic dataset (%.1f per ha)\n", trees.size(), ha,
              double(trees.size()) / ha);
  ASSERT_GT(trees.size(), 100u);
  for (const TreeRow& t : trees) {
    ASSERT_EQ(t.species, "pine");
    ASSERT_GE(t.lon, v[0]);
    ASSERT_LT(t.lon, v[2]);
    ASSERT_GE(t.lat, v[1]);
    ASSERT_LT(t.lat, v[3]);
    // tree_placement.h: log-normal sizes, at least half the s'-scaled least of height_m / width_m.
    ASSERT_GE(t.treeHeight, 0.5 * 8.0 * 0.6 - 1e-3);
    ASSERT_LE(t.treeHeight, 22.0 + 1e-3);
    ASSERT_GE(t.crown, 0.5 * 3.0 * 0.8 - 1e-3);
    ASSERT_LE(t.crown, 1.5 * 7.0 + 1e-3);  // a closed canopy's crowns (tree_placement.h closedCrownM)
  }
  // JSON: the same trees, the same digits.
  const auto j = runVegstream(plants("--bbox " + big + species + " --format json"));
  ASSERT_EQ(j.exitCode, 0) << j.err;
  const json doc = json::parse(j.out);
  EXPECT_EQ(doc["plant_count"], 0);
  ASSERT_EQ(doc["tree_count"].get<size_t>(), trees.size());
  ASSERT_EQ(doc["trees"].size(), trees.size());
  for (size_t i = 0; i < trees.size(); ++i) {
    const json& t = doc["trees"][i];
    ASSERT_EQ((TreeRow{t["lat"], t["lon"], t["height_m"], t["tree_height_m"], t["crown_m"], t["s_prime"], t["species"]}),
              trees[i])
        << i;
  }
  // A smaller box inside: exactly the big box's trees that lie in it (rows near its edges left out).
  const auto b = runVegstream(plants("--bbox " + small + species + " --layer trees"));
  ASSERT_EQ(b.exitCode, 0) << b.err;
  const std::vector<double> s = numbers(small);
  const auto nearEdge = [&](const TreeRow& r) {
    return std::abs(r.lon - s[0]) < 1e-9 || std::abs(r.lon - s[2]) < 1e-9 || std::abs(r.lat - s[1]) < 1e-9 ||
           std::abs(r.lat - s[3]) < 1e-9;
  };
  std::vector<TreeRow> expected, got;
  for (const TreeRow& r : trees)
    if (r.lon >= s[0] && r.lon < s[2] && r.lat >= s[1] && r.lat < s[3] && !nearEdge(r)) expected.push_back(r);
  for (const TreeRow& r : parseTreesCsv(b.out))
    if (!nearEdge(r)) got.push_back(r);
  std::printf("[ figures  ] sub-box: %zu trees, the big box's in it %zu\n", got.size(), expected.size());
  EXPECT_GT(expected.size(), 30u);
  ASSERT_EQ(got, expected);
  // --max-trees binds: one message naming it, exit 2.
  const auto limited = runVegstream(plants("--bbox " + big + species + " --layer trees --max-trees 5"));
  EXPECT_EQ(limited.exitCode, 2) << limited.err;
  EXPECT_EQ(countLines(limited.err), 1) << limited.err;
  EXPECT_NE(limited.err.find("--max-trees"), std::string::npos) << limited.err;
  EXPECT_TRUE(limited.out.empty());
  fs::remove_all(tmp);
}

TEST_F(Plants, UserMistakesAreOneMessageExitTwoAndNoOutput) {
  const fs::path tmp = testTmp("plants_bad");
  fs::create_directories(tmp);
  const fs::path out = tmp / "out.csv";
  std::ofstream(tmp / "bad_species.json") << R"({"species": [{"name": "x"}]})";
  // A copy of the dataset's description without imagery.
  const fs::path noImagery = tmp / "noimagery";
  fs::create_directories(noImagery);
  fs::copy(dir_ / "elevation", noImagery / "elevation", fs::copy_options::recursive);
  {
    std::ifstream in(dir_ / "dataset.json");
    json d = json::parse(in);
    d.erase("imagery");
    std::ofstream(noImagery / "dataset.json") << d.dump(2);
  }
  const std::string box = bbox(50.0), o = " --layer plants --output " + q(out);
  const std::vector<double> v = numbers(box);
  char swapped[160], flat[160], outside[160];
  std::snprintf(swapped, sizeof(swapped), "%.9f,%.9f,%.9f,%.9f", v[2], v[1], v[0], v[3]);
  std::snprintf(flat, sizeof(flat), "%.9f,%.9f,%.9f,%.9f", v[0], v[3], v[2], v[1]);
  std::snprintf(outside, sizeof(outside), "%.9f,%.9f,%.9f,%.9f", v[0] + 1.0, v[1], v[2] + 1.0, v[3]);
  struct Case {
    std::string args, names;
  };
  const std::vector<Case> cases = {
      {plants("--bbox 1,2,3" + o), "--bbox"},
      {plants("--bbox 1,2,x,4" + o), "--bbox"},
      {plants(std::string("--bbox ") + swapped + o), "lon0"},
      {plants(std::string("--bbox ") + flat + o), "lat0"},
      {plants(std::string("--bbox ") + outside + o), "bounds"},
      {"plants " + q(noImagery) + " --bbox " + box + o, "imagery"},
      {plants("--bbox " + box + " --max-plants 1000" + o), "--max-plants"},
      {plants("--bbox " + box + " --max-trees 0" + o), "--max-trees"},
      {plants("--bbox " + box + " --format xml" + o), "--format"},
      {plants("--bbox " + box + " --cluster-size 33" + o), "--cluster-size"},
      {plants("--bbox " + box + " --species " + q(tmp / "bad_species.json") + o), "bad_species.json"},
      {plants("--bbox " + box + " --species " + q(tmp / "missing.json") + o), "missing.json"},
      {plants("--bbox " + box + " --layer plants --output " + q(tmp / "no" / "such" / "dir.csv")), "--output"},
      {plants("--bbox " + box + " --layer plants --output " + q(tmp)), "--output"},
  };
  for (const Case& c : cases) {
    const auto r = runVegstream(c.args);
    EXPECT_EQ(r.exitCode, 2) << c.args << "\n" << r.err;
    EXPECT_EQ(countLines(r.err), 1) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.names), std::string::npos) << c.args << "\n" << r.err;
    EXPECT_TRUE(r.out.empty()) << c.args;
    EXPECT_FALSE(fs::exists(out)) << c.args;
  }
  // --max-plants says how many the box grows (and so what to raise it to).
  const auto r = runVegstream(plants("--bbox " + box + " --layer plants --max-plants 1000"));
  EXPECT_NE(r.err.find("grows"), std::string::npos) << r.err;
  // Nothing left beside the output either (no temporary files).
  size_t leftovers = 0;
  for (const auto& e : fs::directory_iterator(tmp)) leftovers += e.path().filename().string().rfind("out", 0) == 0;
  EXPECT_EQ(leftovers, 0u);
  fs::remove_all(tmp);
}

}  // namespace
}  // namespace vegstream::testing
