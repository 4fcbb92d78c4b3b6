// `vegstream generate`: deterministic from the seed, plausible heights and colours, readable by
// info / query, and bad options refused.

#include <fstream>
#include <map>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "datasets/synthetic_generator.h"
#include "vegetation/colour_score.h"
#include "vegetation/species_catalog.h"
#include "vegetation/species_choice.h"
#include "tests/datasets/query/query_fixture.h"

namespace vegstream::testing {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;

// relative path → bytes of every file under dir.
std::map<std::string, std::string> allFiles(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) files[fs::relative(e.path(), dir).generic_string()] = readWhole(e.path());
  return files;
}

std::string generate(const fs::path& out, int seed) {
  return "generate --out '" + out.string() + "' --name synth --size-km 3 --max-zoom 13 --seed " + std::to_string(seed);
}

TEST(Generate, SameSeedSameBytesOtherSeedDiffers) {
  const fs::path a = testTmp("gen_a"), b = testTmp("gen_b"), c = testTmp("gen_c");
  for (const auto& [dir, seed] : {std::pair{a, 11}, std::pair{b, 11}, std::pair{c, 12}}) {
    const auto r = runVegstream(generate(dir, seed));
    ASSERT_EQ(r.exitCode, 0) << r.err;
  }
  const auto fa = allFiles(a), fb = allFiles(b), fc = allFiles(c);
  EXPECT_GT(fa.size(), 10u);
  EXPECT_EQ(fa, fb);  // identical names and bytes
  size_t differing = 0;
  for (const auto& [name, bytes] : fa)
    if (name.rfind("elevation/13/", 0) == 0) differing += !fc.count(name) || fc.at(name) != bytes;
  EXPECT_GT(differing, 0u);
  for (const auto& d : {a, b, c}) fs::remove_all(d);
}

TEST(Generate, PlausibleTerrainThatInfoAndQueryRead) {
  const fs::path dir = testTmp("gen_info");
  ASSERT_EQ(runVegstream(generate(dir, 3) + " --lat 40.0 --lon -105.6").exitCode, 0);
  const auto info = runVegstream("info '" + dir.string() + "'");
  ASSERT_EQ(info.exitCode, 0) << info.err;
  const json j = json::parse(info.out);
  const double lo = j["height_m"]["min"], hi = j["height_m"]["max"];
  EXPECT_GT(lo, 0.0);
  EXPECT_LT(hi, 5000.0);
  EXPECT_GT(hi - lo, 100.0);  // relief, not a plane
  EXPECT_EQ(j["zoom"]["max"], 13);
  EXPECT_NEAR(j["bounds"]["north"].get<double>() - j["bounds"]["south"].get<double>(), 3.0 / 111.0, 0.001);
  EXPECT_GT(j["tiles"]["elevation"].get<int>(), 4);
  EXPECT_EQ(j["tiles"]["elevation"], j["tiles"]["imagery"]);

  const auto query = runVegstream("query '" + dir.string() + "' --lat 40.0 --lon -105.6");
  ASSERT_EQ(query.exitCode, 0) << query.err;
  const json qj = json::parse(query.out);
  EXPECT_GE(qj["height_m"].get<double>(), lo - 0.01);
  EXPECT_LE(qj["height_m"].get<double>(), hi + 0.01);
  ASSERT_TRUE(qj["color"].is_object());
  // The species the default catalog picks there: a name, and the two best with probabilities
  // that sum to 1 (vegetation/species_choice.h).
  ASSERT_TRUE(qj["species"].is_string()) << query.out;
  ASSERT_TRUE(qj["species_bare"].is_boolean());
  const json& cands = qj["species_candidates"];
  ASSERT_EQ(cands.size(), 2u) << query.out;
  EXPECT_EQ(cands[0]["name"], qj["species"]);
  EXPECT_GE(cands[0]["probability"].get<double>(), cands[1]["probability"].get<double>());
  EXPECT_NEAR(cands[0]["probability"].get<double>() + cands[1]["probability"].get<double>(), 1.0, 1e-6);

  // --species: another catalog (one species: it always wins) …
  const fs::path one = dir / "one_species.json";
  std::ofstream(one) << R"({"species": [{"name": "moss", "reference": {"srgb": "#406030"},
    "weights": {"h": 1, "s": 1, "v": 1}, "p": 2, "kind": "grass", "height_m": {"min": 0.01, "max": 0.02},
    "stiffness": {"min": 1, "max": 2}, "width_m": {"min": 0.001, "max": 0.002},
    "colour_modulation": {"min": 1, "max": 1}}]})";
  const auto custom =
      runVegstream("query '" + dir.string() + "' --lat 40.0 --lon -105.6 --species '" + one.string() + "'");
  ASSERT_EQ(custom.exitCode, 0) << custom.err;
  const json cj = json::parse(custom.out);
  EXPECT_EQ(cj["species"], "moss");
  ASSERT_EQ(cj["species_candidates"].size(), 1u);
  EXPECT_EQ(cj["species_candidates"][0]["probability"], 1.0);
  // … and a bad one: one message naming the file and the field, exit 2, nothing on stdout.
  const fs::path bad = dir / "bad_species.json";
  std::ofstream(bad) << R"({"species": [{"name": "moss", "reference": {"srgb": "#406030"}, "wieghts": {}}]})";
  for (const fs::path& f : {bad, dir / "missing_species.json"}) {
    const auto r = runVegstream("query '" + dir.string() + "' --lat 40.0 --lon -105.6 --species '" + f.string() + "'");
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_EQ(countLines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(f.filename().string()), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
  const auto badRun =
      runVegstream("query '" + dir.string() + "' --lat 40.0 --lon -105.6 --species '" + bad.string() + "'");
  EXPECT_NE(badRun.err.find("species[0].wieghts: unknown key"), std::string::npos) << badRun.err;
  fs::remove_all(dir);
}

TEST(Generate, ColoursFollowHeightAndSlope) {
  const datasets::SyntheticTerrain t(1);
  const auto valley = t.color(0, 0, 800.0, 0.05), cliff = t.color(0, 0, 1500.0, 1.2), peak = t.color(0, 0, 3400.0, 0.2);
  EXPECT_GT(valley[1], valley[0]);  // green
  EXPECT_GT(valley[1], valley[2]);
  EXPECT_NEAR(cliff[0], cliff[1], 20);  // grey rock
  EXPECT_GT(peak[2], 220);              // snow
  EXPECT_GT(peak[0], 220);
}

// The biomes grow what they are with the default species catalog (config/species.json): valley
// floors grass, the lower slopes mostly conifers (forest), alpine meadows grass, cliffs and snow
// nothing (a bare entry wins). Colours of a 40 × 40 grid over 10 km, per biome; the winner of eq. 17's two
// best must also win clearly (probability ≥ 0.75) on grass and conifer ground.
TEST(Generate, TheDefaultCatalogGrowsEachBiomesPlants) {
  const datasets::SyntheticTerrain t(1);
  const vegetation::SpeciesCatalog& catalog = vegetation::defaultSpeciesCatalog();
  struct Biome {
    const char* name;
    double heightM, slopeRad;
  };
  for (const Biome& b : {Biome{"valley", 800.0, 0.05}, Biome{"lower slopes", 1200.0, 0.2},
                         Biome{"alpine meadow", 2100.0, 0.1},
                         Biome{"cliff", 1500.0, 1.2}, Biome{"snow", 3400.0, 0.2}}) {
    SCOPED_TRACE(b.name);
    std::map<std::string, int> won;
    int clear = 0, total = 0;
    for (int i = 0; i < 40; ++i)
      for (int j = 0; j < 40; ++j) {
        const auto c = t.color(-5000.0 + 250.0 * i, -5000.0 + 250.0 * j, b.heightM, b.slopeRad);
        const auto k = vegetation::speciesCandidates(catalog, vegetation::hsvFromSrgb8(c[0], c[1], c[2]));
        ASSERT_GE(k.first, 0);
        const auto& sp = catalog.species[static_cast<size_t>(k.first)];
        ++won[sp.bare ? std::string("bare") : sp.name];
        clear += k.secondRatio <= 0.25f;
        ++total;
      }
    const std::string biome = b.name;
    if (biome == "valley") {
      EXPECT_GE(won["grass"], total * 9 / 10) << "meadows";
      EXPECT_EQ(won["grass"] + won["conifer"], total) << "with a few forest patches";
    } else if (biome == "lower slopes") {
      EXPECT_GE(won["conifer"], total / 2) << "forest";
      EXPECT_EQ(won["grass"] + won["conifer"], total) << "with clearings";
    } else if (biome == "alpine meadow") {
      EXPECT_GE(won["grass"], total * 95 / 100);
    } else {
      EXPECT_EQ(won["bare"], total);
    }
    if (biome != "cliff" && biome != "snow") {
      EXPECT_GE(clear, total * 80 / 100) << "clear winners";
    }
  }
}

TEST(Generate, BadOptionsAreUserErrors) {
  const fs::path dir = testTmp("gen_bad");
  for (const char* extra : {" --size-km 0", " --lat 89", " --encoding png"}) {
    const auto r = runVegstream("generate --out '" + dir.string() + "'" + extra);
    EXPECT_EQ(r.exitCode, 2) << extra;
    EXPECT_EQ(countLines(r.err), 1) << r.err;
    EXPECT_FALSE(fs::exists(dir));
  }
}

}  // namespace
}  // namespace vegstream::testing
