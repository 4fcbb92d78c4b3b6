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

}  // namespace
}  // namespace vegstream::vegetation
