// vegetation/species_catalog.h (core seed ../shared/seeds/001_3eca9f2c7752e4fb.txt §3.3): the
// shipped catalog parses, and every kind of bad input is one error naming source and field.

#include "vegetation/species_catalog.h"

#include <functional>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace vegstream::vegetation {
namespace {
using nlohmann::json;

json goodSpecies() {
  return json::parse(R"({
    "name": "grass", "reference": {"h_deg": 90, "s": 0.3, "v": 0.4}, "weights": {"h": 2, "s": 1, "v": 0.5},
    "p": 3, "kind": "grass", "height_m": {"min": 0.2, "max": 0.5}, "stiffness": {"min": 0.8, "max": 1.6},
    "width_m": {"min": 0.005, "max": 0.01}, "colour_modulation": {"min": 0.9, "max": 1.1}})");
}

json catalogOf(json species) { return json{{"species", json::array({std::move(species)})}}; }

Result<SpeciesCatalog> parse(const json& j) { return parseSpeciesCatalog(j.dump(), "species.json"); }

// The error for `j`, which must fail.
std::string errorOf(const json& j) {
  auto r = parse(j);
  EXPECT_FALSE(r.ok());
  if (r.ok()) return "";
  EXPECT_EQ(r.error().kind, ErrorKind::InvalidInput);
  return r.error().message;
}

TEST(SpeciesCatalog, TheShippedDefaultParses) {
  auto r = parseSpeciesCatalog(defaultSpeciesCatalogJson(), "config/species.json");
  ASSERT_TRUE(r.ok()) << r.error().message;
  const SpeciesCatalog& c = defaultSpeciesCatalog();
  ASSERT_GE(c.species.size(), 4u);
  EXPECT_LE(c.species.size(), kMaxSpecies);
  int bare = 0;
  bool kinds[4] = {};
  for (const Species& s : c.species) {
    bare += s.bare ? 1 : 0;
    if (!s.bare) kinds[static_cast<int>(s.kind)] = true;
  }
  EXPECT_GE(bare, 2);
  for (bool k : kinds) EXPECT_TRUE(k) << "every renderer kind has a species";
  // Issue 18: a meadow is dense (hundreds of blades per m²), gravel sparse; every species that
  // grows has its own density and horizon.
  for (const Species& s : c.species)
    if (s.name == "grass") {
      EXPECT_GE(s.densityM2, 200.0f);
      EXPECT_GE(s.horizonM, 100.0f);
    } else if (s.kind == RendererKind::Gravel && !s.bare) {
      EXPECT_LT(s.densityM2, 50.0f);
    }
  EXPECT_EQ(densestGroundDensity(c), 400.0f);
  EXPECT_GE(farthestHorizon(c), 150.0f);
  // Issue 20: tree species on their own grid and horizon; the plants' figures leave them out.
  // Issue 41 item 4: six of them, two claiming the ground by colour (tree_niche.h).
  int trees = 0;
  for (const Species& s : c.species)
    if (isTree(s)) {
      ++trees;
      EXPECT_GE(s.horizonM, 3000.0f) << s.name;
      EXPECT_GE(s.tree.branchLevels, 2u) << s.name;
      EXPECT_FLOAT_EQ(s.densityM2, s.tree.densityHa / 1e4f) << s.name;
    }
  EXPECT_EQ(trees, 6);
  int claiming = 0;
  for (const Species& s : c.species) claiming += isTree(s) && s.tree.claimsGround;
  EXPECT_EQ(claiming, 2);
  EXPECT_EQ(farthestHorizon(c), 150.0f) << "the grass's: trees excluded";
  EXPECT_EQ(densestTreeDensityHa(c), 260.0f);
  EXPECT_FLOAT_EQ(largestTreeSpacing(c), 4.1f);
  EXPECT_EQ(farthestTreeHorizon(c), 3000.0f);
  EXPECT_TRUE(hasTrees(c));
}

TEST(SpeciesCatalog, ReadsHsvInDegreesAndSrgb) {
  json s = goodSpecies();
  auto r = parse(catalogOf(s));
  ASSERT_TRUE(r.ok()) << r.error().message;
  const Species& sp = r->species[0];
  EXPECT_FLOAT_EQ(sp.score.reference.x, 0.25f);
  EXPECT_FLOAT_EQ(sp.score.reference.y, 0.3f);
  EXPECT_FLOAT_EQ(sp.score.weights.x, 2.0f);
  EXPECT_EQ(sp.kind, RendererKind::Grass);
  EXPECT_FLOAT_EQ(sp.heightM.max, 0.5f);
  EXPECT_FALSE(sp.bare);
  EXPECT_EQ(sp.threshold, 0.0f);

  s["reference"] = {{"srgb", "#ff0000"}};
  r = parse(catalogOf(s));
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_FLOAT_EQ(r->species[0].score.reference.x, 0.0f);
  EXPECT_FLOAT_EQ(r->species[0].score.reference.y, 1.0f);
  EXPECT_FLOAT_EQ(r->species[0].score.reference.z, 1.0f);

  s["reference"] = {{"h_deg", 360}, {"s", 0.5}, {"v", 0.5}};  // 360° is 0°
  r = parse(catalogOf(s));
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(r->species[0].score.reference.x, 0.0f);
}

TEST(SpeciesCatalog, BareEntriesNeedNoPlantFields) {
  json bare = {{"name", "rock"},
               {"reference", {{"h_deg", 0}, {"s", 0}, {"v", 0.5}}},
               {"weights", {{"h", 0}, {"s", 1}, {"v", 1}}},
               {"p", 2},
               {"bare", true}};
  json j = {{"about", "x"}, {"species", json::array({goodSpecies(), bare})}};
  auto r = parse(j);
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_TRUE(r->species[1].bare);
  // …but a catalog of bare soil only grows nothing.
  EXPECT_NE(errorOf(json{{"species", json::array({bare})}}).find("species: every entry is bare"), std::string::npos);
}

struct BadCase {
  const char* what;
  std::function<void(json&)> edit;  // applied to the single species
  const char* expected;             // a substring of the message
};

TEST(SpeciesCatalog, EachBadInputNamesTheFileAndField) {
  const BadCase cases[] = {
      {"typo key", [](json& s) { s["hieght_m"] = 1; }, "species.json: species[0].hieght_m: unknown key"},
      {"nested typo", [](json& s) { s["weights"]["hue"] = 1; }, "species[0].weights.hue: unknown key"},
      {"min > max",
       [](json& s) {
         s["height_m"] = {{"min", 0.3}, {"max", 0.1}};
       },
       "species[0].height_m.max: must be ≥ min (got 0.1 < 0.3)"},
      {"zero height", [](json& s) { s["height_m"]["min"] = 0; }, "species[0].height_m.min: must be > 0"},
      {"negative stiffness", [](json& s) { s["stiffness"]["min"] = -1; }, "species[0].stiffness.min: must be > 0"},
      {"stiffness that buries the tip", [](json& s) { s["stiffness"]["min"] = 0.4; },
       "species[0].stiffness.min: relative to the buckling stiffness k_c, 0.4 bends the blade's tip below its root"},
      {"phototropism above 1", [](json& s) { s["phototropism"] = 1.5; }, "species[0].phototropism: must be in 0 … 1"},
      {"zero density", [](json& s) { s["density_m2"] = 0; },
       "species[0].density_m2: must be > 0 and ≤ 10000 plants per m²"},
      {"negative density", [](json& s) { s["density_m2"] = -3; }, "species[0].density_m2: must be > 0"},
      {"zero horizon", [](json& s) { s["horizon_m"] = 0; }, "species[0].horizon_m: must be > 0 and ≤ 20000 metres"},
      {"horizon string", [](json& s) { s["horizon_m"] = "far"; }, "species[0].horizon_m: must be a number"},
      {"p zero", [](json& s) { s["p"] = 0; }, "species[0].p: must be > 0"},
      {"p string", [](json& s) { s["p"] = "3"; }, "species[0].p: must be a number"},
      {"negative weight", [](json& s) { s["weights"]["s"] = -0.5; }, "species[0].weights.s: must be ≥ 0"},
      {"all weights zero",
       [](json& s) {
         s["weights"] = {{"h", 0}, {"s", 0}, {"v", 0}};
       },
       "species[0].weights: must not all be 0"},
      {"hue out of range", [](json& s) { s["reference"]["h_deg"] = 400; },
       "species[0].reference.h_deg: must be in 0 … 360"},
      {"s out of range", [](json& s) { s["reference"]["s"] = 1.5; }, "species[0].reference.s: must be in 0 … 1"},
      {"bad srgb",
       [](json& s) {
         s["reference"] = {{"srgb", "#12345g"}};
       },
       "species[0].reference.srgb: must be a colour"},
      {"missing reference", [](json& s) { s.erase("reference"); }, "species[0].reference: is missing"},
      {"unknown kind", [](json& s) { s["kind"] = "bush"; }, "species[0].kind: must be \"grass\""},
      {"missing kind", [](json& s) { s.erase("kind"); }, "species[0].kind: is missing"},
      {"missing range", [](json& s) { s.erase("width_m"); }, "species[0].width_m: is missing"},
      {"negative threshold", [](json& s) { s["threshold"] = -1; }, "species[0].threshold: must be ≥ 0"},
      {"bare not bool", [](json& s) { s["bare"] = 1; }, "species[0].bare: must be true or false"},
      {"empty name", [](json& s) { s["name"] = ""; }, "species[0].name: must be a non-empty string"},
      {"modulation too big", [](json& s) { s["colour_modulation"]["max"] = 9; },
       "species[0].colour_modulation.max: must be in 0 … 4"},
  };
  for (const BadCase& c : cases) {
    json s = goodSpecies();
    c.edit(s);
    const std::string m = errorOf(catalogOf(s));
    EXPECT_NE(m.find(c.expected), std::string::npos) << c.what << ": " << m;
    EXPECT_EQ(m.rfind("species.json: ", 0), 0u) << c.what << ": " << m;
  }
}

TEST(SpeciesCatalog, TopLevelProblemsAreNamed) {
  EXPECT_NE(errorOf(json{{"specis", json::array()}}).find("species.json: specis: unknown key"), std::string::npos);
  EXPECT_NE(errorOf(json::object()).find("species: is missing"), std::string::npos);
  EXPECT_NE(errorOf(json{{"species", json::array()}}).find("species: must be an array of 1 … 16"), std::string::npos);
  json many = json::array();
  for (int i = 0; i < 17; ++i) {
    json s = goodSpecies();
    s["name"] = "s" + std::to_string(i);
    many.push_back(s);
  }
  EXPECT_NE(errorOf(json{{"species", many}}).find("(got 17)"), std::string::npos);
  json dup = json{{"species", json::array({goodSpecies(), goodSpecies()})}};
  EXPECT_NE(errorOf(dup).find("species[1].name: duplicate name \"grass\""), std::string::npos);

  auto r = parseSpeciesCatalog("{ \"species\": [ ", "broken.json");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().message.rfind("broken.json: not valid JSON", 0), 0u) << r.error().message;
  r = parseSpeciesCatalog("[1, 2]", "list.json");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().message.rfind("list.json: ", 0), 0u);
}

TEST(SpeciesCatalog, LoadNamesAMissingFile) {
  auto r = loadSpeciesCatalog("/nonexistent/species.json");
  ASSERT_FALSE(r.ok());
  EXPECT_TRUE(r.error().isUserError());
  EXPECT_NE(r.error().message.find("/nonexistent/species.json"), std::string::npos) << r.error().message;
}

json goodTree() {
  return json::parse(R"({
    "name": "oak", "reference": {"h_deg": 100, "s": 0.4, "v": 0.3}, "weights": {"h": 2, "s": 1, "v": 1},
    "p": 3, "kind": "tree", "height_m": {"min": 6, "max": 15}, "stiffness": {"min": 5, "max": 9},
    "width_m": {"min": 5, "max": 12}, "colour_modulation": {"min": 0.9, "max": 1.1},
    "tree": {"form": "broadleaf", "density_ha": 80, "spacing_m": 5}})");
}

TEST(SpeciesCatalog, ReadsATreeWithDefaultsForWhatItLeavesOut) {
  json t = goodTree();
  auto r = parse(json{{"species", json::array({goodSpecies(), t})}});
  ASSERT_TRUE(r.ok()) << r.error().message;
  const Species& oak = r->species[1];
  EXPECT_TRUE(isTree(oak));
  EXPECT_FALSE(isTree(r->species[0]));
  EXPECT_EQ(oak.tree.form, TreeForm::Broadleaf);
  EXPECT_EQ(oak.tree.densityHa, 80.0f);
  EXPECT_EQ(oak.tree.spacingM, 5.0f);
  EXPECT_EQ(oak.horizonM, kDefaultTreeHorizonM);
  const TreeParams defaults;
  EXPECT_EQ(oak.tree.branchLevels, defaults.branchLevels);
  EXPECT_EQ(oak.tree.leavesPerTwig, defaults.leavesPerTwig);
  EXPECT_EQ(oak.tree.leafColour[1], defaults.leafColour[1]);

  t["tree"]["branch_levels"] = 3;
  t["tree"]["branches"] = 12;
  t["tree"]["twigs"] = 4;
  t["tree"]["branch_angle_deg"] = 50;
  t["tree"]["trunk_radius_m"] = 0.4;
  t["tree"]["taper"] = 0.3;
  t["tree"]["leaf_size_m"] = 0.2;
  t["tree"]["leaves_per_twig"] = 20;
  t["tree"]["leaf_colour"] = "#ff8000";
  t["tree"]["bark_colour"] = "#000000";
  t["tree"]["translucency"] = 0.7;
  t["tree"]["form"] = "conifer";
  t["horizon_m"] = 5000;
  r = parse(json{{"species", json::array({goodSpecies(), t})}});
  ASSERT_TRUE(r.ok()) << r.error().message;
  const TreeParams& p = r->species[1].tree;
  EXPECT_EQ(p.form, TreeForm::Conifer);
  EXPECT_EQ(p.branchLevels, 3u);
  EXPECT_EQ(p.branches, 12u);
  EXPECT_EQ(p.twigs, 4u);
  EXPECT_EQ(p.branchAngleDeg, 50.0f);
  EXPECT_FLOAT_EQ(p.trunkRadiusM, 0.4f);
  EXPECT_FLOAT_EQ(p.taper, 0.3f);
  EXPECT_FLOAT_EQ(p.leafSizeM, 0.2f);
  EXPECT_EQ(p.leavesPerTwig, 20u);
  // sRGB → linear: 0xff → 1, 0x80 → 0.2158, 0 → 0.
  EXPECT_FLOAT_EQ(p.leafColour[0], 1.0f);
  EXPECT_NEAR(p.leafColour[1], 0.2158, 1e-4);
  EXPECT_EQ(p.leafColour[2], 0.0f);
  EXPECT_EQ(p.barkColour[0], 0.0f);
  EXPECT_FLOAT_EQ(p.translucency, 0.7f);
  EXPECT_EQ(r->species[1].horizonM, 5000.0f);
  // The plants' figures leave the tree out; the trees' have it.
  EXPECT_EQ(densestGroundDensity(*r), 10.0f);
  EXPECT_EQ(farthestHorizon(*r), 150.0f);
  EXPECT_EQ(farthestTreeHorizon(*r), 5000.0f);
}

TEST(SpeciesCatalog, EachBadTreeNamesTheFileAndField) {
  const BadCase cases[] = {
      {"no tree object", [](json& t) { t.erase("tree"); }, "species[1].tree: is missing"},
      {"negative height", [](json& t) { t["height_m"]["min"] = -6; }, "species[1].height_m.min: must be > 0"},
      {"inverted height",
       [](json& t) {
         t["height_m"] = {{"min", 15}, {"max", 6}};
       },
       "species[1].height_m.max: must be ≥ min (got 6 < 15)"},
      {"zero density", [](json& t) { t["tree"]["density_ha"] = 0; },
       "species[1].tree.density_ha: must be > 0 and ≤ 10000 trees per hectare (got 0)"},
      {"negative density", [](json& t) { t["tree"]["density_ha"] = -80; }, "species[1].tree.density_ha: must be > 0"},
      {"missing density", [](json& t) { t["tree"].erase("density_ha"); }, "species[1].tree.density_ha: is missing"},
      {"missing spacing", [](json& t) { t["tree"].erase("spacing_m"); }, "species[1].tree.spacing_m: is missing"},
      {"too many branch levels", [](json& t) { t["tree"]["branch_levels"] = 4; },
       "species[1].tree.branch_levels: more branch levels than the model supports (at most 3"},
      {"too few branch levels", [](json& t) { t["tree"]["branch_levels"] = 1; },
       "species[1].tree.branch_levels: must be 2 … 3"},
      {"fractional branches", [](json& t) { t["tree"]["branches"] = 4.5; },
       "species[1].tree.branches: must be a whole number"},
      {"unknown form", [](json& t) { t["tree"]["form"] = "palm"; }, "species[1].tree.form: must be \"conifer\""},
      {"missing form", [](json& t) { t["tree"].erase("form"); }, "species[1].tree.form: is missing"},
      {"bad leaf colour", [](json& t) { t["tree"]["leaf_colour"] = "green"; },
       "species[1].tree.leaf_colour: must be a colour"},
      {"tree typo", [](json& t) { t["tree"]["spacing"] = 3; }, "species[1].tree.spacing: unknown key"},
      {"taper zero", [](json& t) { t["tree"]["taper"] = 0; }, "species[1].tree.taper: must be in 0.1 … 0.8"},
      {"density_m2 on a tree", [](json& t) { t["density_m2"] = 0.01; },
       "species[1].density_m2: not for trees (give tree.density_ha"},
      // The conifer-like density 180 per ha sets cells of 7.07 m: at most 4.94 m between trees.
      {"spacing too large",
       [](json& t) {
         t["tree"]["density_ha"] = 180;
         t["tree"]["spacing_m"] = 6;
       },
       "species[1].tree.spacing_m: 6 m does not fit the placement grid"},
      {"horizon shorter than the grass's", [](json& t) { t["horizon_m"] = 100; },
       "species[1].horizon_m: a tree horizon shorter than the grass's (150 m)"},
  };
  for (const BadCase& c : cases) {
    json t = goodTree();
    c.edit(t);
    const std::string m = errorOf(json{{"species", json::array({goodSpecies(), t})}});
    EXPECT_NE(m.find(c.expected), std::string::npos) << c.what << ": " << m;
    EXPECT_EQ(m.rfind("species.json: ", 0), 0u) << c.what << ": " << m;
  }
  // The largest spacing that fits is named; a tree object on grass is refused.
  json t = goodTree();
  t["tree"]["density_ha"] = 180;
  t["tree"]["spacing_m"] = 6;
  EXPECT_NE(errorOf(json{{"species", json::array({t})}}).find("at most 4.94 m"), std::string::npos);
  json g = goodSpecies();
  g["tree"] = goodTree()["tree"];
  EXPECT_NE(errorOf(catalogOf(g)).find("species[0].tree: only for species of kind \"tree\""), std::string::npos);
  // Spacing is checked against the densest tree species, not only its own density.
  json dense = goodTree(), sparse = goodTree();
  dense["name"] = "dense";
  dense["tree"]["density_ha"] = 400;  // cells of 4.74 m: at most 3.32 m
  dense["tree"]["spacing_m"] = 3;
  sparse["tree"]["density_ha"] = 20;
  sparse["tree"]["spacing_m"] = 5;
  EXPECT_NE(errorOf(json{{"species", json::array({dense, sparse})}}).find("species[1].tree.spacing_m"),
            std::string::npos);
}

}  // namespace
}  // namespace vegstream::vegetation
