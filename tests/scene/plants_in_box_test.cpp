// scene::plantsInBox (scene/plants_in_box.h) in process, on a small synthetic dataset: every
// plant lies in the half-open box, on the ground the dataset describes, with a catalog species
// and parameters from its ranges; two calls agree; a sub-box gives exactly the big box's plants
// that lie in it (core seed ../shared/seeds/001_3eca9f2c7752e4fb.txt §2.2: a plant depends on its
// triangle alone); tiles go through the streamer — from a directory or over HTTP alike, a missing
// tile drawn from its parent, a corrupt one an error naming it; mistakes are errors naming the box
// and the limit.

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "datasets/dataset_reader.h"
#include "datasets/progress.h"
#include "datasets/synthetic_generator.h"
#include "geo/xyz_tiles.h"
#include "scene/plants_in_box.h"
#include "vegetation/canopy_cells.h"
#include "tests/support/nginx_server.h"

namespace vegstream::scene {
namespace {
namespace fs = std::filesystem;

// VEGSTREAM_TEST_TMP/<suite>_<name>/, made fresh.
fs::path ownTestDir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::path(VEGSTREAM_TEST_TMP) / (std::string(info->test_suite_name()) + "_" + info->name());
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// A 2 km synthetic dataset (max zoom 13) in `dir`.
fs::path makeDataset(const fs::path& dir) {
  datasets::SyntheticOptions o;
  o.out = dir / "synth";
  o.sizeKm = 2.0;
  o.maxZoom = 13;
  o.seed = 7;
  o.threads = 1;
  datasets::NullProgress progress;
  const auto meta = datasets::generateSyntheticDataset(o, makeNullLogger(), progress);
  EXPECT_TRUE(meta.ok()) << (meta.ok() ? "" : meta.error().message);
  return o.out;
}

// A square box of half-side halfM metres around (lat, lon).
geo::GeoBounds boxAround(double lat, double lon, double halfM) {
  const double dLat = halfM / 111000.0, dLon = halfM / (111000.0 * std::cos(lat * M_PI / 180.0));
  return {lon - dLon, lat - dLat, lon + dLon, lat + dLat};
}

constexpr double kLat = 46.55, kLon = 7.95;  // the synthetic dataset's centre

bool inBox(const BoxPlant& p, const geo::GeoBounds& b) {
  return p.at.lonDeg >= b.westDeg && p.at.lonDeg < b.eastDeg && p.at.latDeg >= b.southDeg && p.at.latDeg < b.northDeg;
}

auto tie(const BoxPlant& p) {
  return std::make_tuple(p.at.latDeg, p.at.lonDeg, p.at.heightM, p.species, p.heightM, p.stiffness, p.sPrime);
}

TEST(PlantsInBox, AreInTheBoxOnTheGroundWithCatalogSpeciesAndRepeatable) {
  const fs::path dataset = makeDataset(ownTestDir());
  const auto& catalog = vegetation::defaultSpeciesCatalog();
  const geo::GeoBounds box = boxAround(kLat, kLon, 40.0);
  const auto r = plantsInBox(dataset.string(), box, catalog, {});
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(r->datasetName, "synth");
  EXPECT_GT(r->seedTriangles, 100u);
  ASSERT_GT(r->plants.size(), 10000u) << "80 m × 80 m of meadow at full density";
  auto reader = datasets::DatasetReader::open(dataset);
  ASSERT_TRUE(reader.ok());
  double worstGroundM = 0.0;
  for (const BoxPlant& p : r->plants) {
    ASSERT_TRUE(inBox(p, box)) << p.at.latDeg << ", " << p.at.lonDeg;
    ASSERT_LT(p.species, catalog.species.size());
    const vegetation::Species& s = catalog.species[p.species];
    EXPECT_FALSE(s.bare) << "bare soil grows nothing";
    // The species ranges scaled by s′ (vegetation/species_catalog.h sPrimeFactor), s′ in [0, 1].
    EXPECT_GE(p.sPrime, 0.0f);
    EXPECT_LE(p.sPrime, 1.0f);
    const float hs = vegetation::sPrimeFactor(vegetation::kSPrimeHeightLo, p.sPrime);
    const float ks = vegetation::sPrimeFactor(vegetation::kSPrimeStiffnessLo, p.sPrime);
    EXPECT_GE(p.heightM, s.heightM.min * hs * 0.9999f);
    EXPECT_LE(p.heightM, s.heightM.max * hs * 1.0001f);
    EXPECT_GE(p.stiffness, s.stiffness.min * ks * 0.9999f);
    EXPECT_LE(p.stiffness, s.stiffness.max * ks * 1.0001f);
    // The root is on the seed triangle, a plane through three height samples a few metres apart:
    // within half a metre of the dataset's bilinear ground under it (0.11 m seen).
    const auto ground = reader->heightAt(p.at.latDeg, p.at.lonDeg);
    ASSERT_TRUE(ground.ok());
    worstGroundM = std::max(worstGroundM, std::abs(p.at.heightM - *ground));
  }
  std::printf("worst root vs bilinear ground: %.3f m\n", worstGroundM);
  EXPECT_LT(worstGroundM, 0.5);
  const auto again = plantsInBox(dataset.string(), box, catalog, {});
  ASSERT_TRUE(again.ok());
  ASSERT_EQ(again->plants.size(), r->plants.size());
  for (size_t i = 0; i < r->plants.size(); ++i) ASSERT_EQ(tie(again->plants[i]), tie(r->plants[i])) << i;
}

TEST(PlantsInBox, ASubBoxGivesExactlyTheBigBoxsPlantsInIt) {
  const fs::path dataset = makeDataset(ownTestDir());
  const auto& catalog = vegetation::defaultSpeciesCatalog();
  const geo::GeoBounds big = boxAround(kLat, kLon, 40.0), sub = boxAround(kLat + 0.0001, kLon - 0.0002, 12.0);
  const auto all = plantsInBox(dataset.string(), big, catalog, {});
  const auto part = plantsInBox(dataset.string(), sub, catalog, {});
  ASSERT_TRUE(all.ok() && part.ok());
  std::vector<std::tuple<double, double, double, uint32_t, float, float, float>> expected, got;
  for (const BoxPlant& p : all->plants)
    if (inBox(p, sub)) expected.push_back(tie(p));
  for (const BoxPlant& p : part->plants) got.push_back(tie(p));
  std::sort(expected.begin(), expected.end());
  std::sort(got.begin(), got.end());
  ASSERT_GT(got.size(), 1000u);
  EXPECT_EQ(got, expected);
}

// Crowns over the meadow (scene/trees_in_box.h gives them in a flight's listing): the plants are
// those the same box grows without them, less about 85 % of those under a crown's middle; 3 m
// (a cluster's reach: groups are thinned whole, by their centre) beyond every crown, the same
// plants; and a sub-box still lists exactly the big box's plants in it.
TEST(PlantsInBox, PlantsThinUnderTheCrownsAndNowhereElse) {
  const fs::path dataset = makeDataset(ownTestDir());
  const auto& catalog = vegetation::defaultSpeciesCatalog();
  const geo::GeoBounds big = boxAround(kLat, kLon, 40.0), sub = boxAround(kLat + 0.0001, kLon - 0.0002, 12.0);
  PlantsInBoxOptions options;
  const double dLat = 1.0 / 111000.0, dLon = 1.0 / (111000.0 * std::cos(kLat * M_PI / 180.0));
  for (double north = -30.0; north <= 30.0; north += 20.0)  // 16 crowns of 12 m, 20 m apart
    for (double east = -30.0; east <= 30.0; east += 20.0)
      options.crowns.push_back({{kLat + north * dLat, kLon + east * dLon, 0.0}, 12.0f});
  const auto bare = plantsInBox(dataset.string(), big, catalog, {});
  const auto under = plantsInBox(dataset.string(), big, catalog, options);
  const auto part = plantsInBox(dataset.string(), sub, catalog, options);
  ASSERT_TRUE(bare.ok() && under.ok() && part.ok());
  // Metres from the nearest trunk, on the local tangent plane.
  const auto nearest = [&](const BoxPlant& p) {
    double best = 1e9;
    for (const BoxCrown& c : options.crowns)
      best = std::min(best, std::hypot((p.at.lonDeg - c.at.lonDeg) / dLon, (p.at.latDeg - c.at.latDeg) / dLat));
    return best;
  };
  using Key = std::tuple<double, double, double, uint32_t, float, float, float>;
  std::vector<Key> farBare, farUnder, all(0), subExpected, subGot;
  size_t innerBare = 0, innerUnder = 0;
  for (const BoxPlant& p : bare->plants) {
    if (nearest(p) > 9.0) farBare.push_back(tie(p));
    if (nearest(p) < 3.4) ++innerBare;
    all.push_back(tie(p));
  }
  std::sort(all.begin(), all.end());
  for (const BoxPlant& p : under->plants) {
    ASSERT_TRUE(std::binary_search(all.begin(), all.end(), tie(p))) << "a plant the bare ground does not grow";
    if (nearest(p) > 9.0) farUnder.push_back(tie(p));
    if (nearest(p) < 3.4) ++innerUnder;
    if (inBox(p, sub)) subExpected.push_back(tie(p));
  }
  for (const BoxPlant& p : part->plants) subGot.push_back(tie(p));
  std::sort(subExpected.begin(), subExpected.end());
  std::sort(subGot.begin(), subGot.end());
  std::printf("under the crowns' middles: %zu of %zu plants kept; %zu plants beyond the crowns, the same\n",
              innerUnder, innerBare, farUnder.size());
  EXPECT_EQ(farUnder, farBare);
  ASSERT_GT(innerBare, 8000u);
  EXPECT_NEAR(double(innerUnder) / double(innerBare), 1.0 - vegetation::kCanopyThinning, 0.05);
  EXPECT_EQ(subGot, subExpected);
}

// The dataset served by nginx: the same plants, bit for bit, as from the directory (the ground
// comes through the streamer, whatever the source).
TEST(PlantsInBox, OverHttpTheSameAsFromTheDirectory) {
  const fs::path dir = ownTestDir();
  const fs::path dataset = makeDataset(dir);
  auto server = testing::NginxServer::start(dataset, dir / "nginx");
  ASSERT_TRUE(server.ok()) << server.error().message;
  const auto& catalog = vegetation::defaultSpeciesCatalog();
  const geo::GeoBounds box = boxAround(kLat, kLon, 15.0);
  const auto local = plantsInBox(dataset.string(), box, catalog, {});
  const auto http = plantsInBox((*server)->baseUrl(), box, catalog, {});
  ASSERT_TRUE(local.ok()) << local.error().message;
  ASSERT_TRUE(http.ok()) << http.error().message;
  ASSERT_GT(local->plants.size(), 1000u);
  ASSERT_EQ(http->plants.size(), local->plants.size());
  for (size_t i = 0; i < local->plants.size(); ++i) ASSERT_EQ(tie(http->plants[i]), tie(local->plants[i])) << i;
  EXPECT_FALSE((*server)->accessLog().empty()) << "the tiles came over HTTP";
}

// A tile the dataset lacks is drawn from its parent (as a flight draws it); one that is corrupt is
// an error naming it, never silently its parent's ground.
TEST(PlantsInBox, MissingTilesComeFromTheirParentCorruptOnesAreErrors) {
  const fs::path dataset = makeDataset(ownTestDir());
  const auto& catalog = vegetation::defaultSpeciesCatalog();
  auto reader = datasets::DatasetReader::open(dataset);
  ASSERT_TRUE(reader.ok());
  const datasets::DatasetMeta meta = reader->meta();
  const geo::GeoBounds box = boxAround(kLat, kLon, 20.0);
  const auto whole = plantsInBox(dataset.string(), box, catalog, {});
  ASSERT_TRUE(whole.ok()) << whole.error().message;
  const std::vector<geo::TileId> under = geo::tilesCovering(box, meta.maxZoom);
  ASSERT_FALSE(under.empty());
  const fs::path tile = datasets::elevationTilePath(dataset, under.front());
  const fs::path kept = dataset.parent_path() / "kept.png";
  fs::rename(tile, kept);
  const auto fromParent = plantsInBox(dataset.string(), box, catalog, {});
  ASSERT_TRUE(fromParent.ok()) << fromParent.error().message;
  ASSERT_FALSE(fromParent->plants.empty());
  size_t moved = 0;  // the parent's coarser heights put roots elsewhere
  for (size_t i = 0; i < std::min(whole->plants.size(), fromParent->plants.size()); ++i)
    moved += whole->plants[i].at.heightM != fromParent->plants[i].at.heightM;
  EXPECT_GT(moved, 0u);

  // The same tile, cut short: an error naming it, not its parent's ground.
  {
    std::ifstream in(kept, std::ios::binary);
    std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ofstream(tile, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size() / 2));
  }
  const auto corrupt = plantsInBox(dataset.string(), box, catalog, {});
  ASSERT_FALSE(corrupt.ok());
  EXPECT_EQ(corrupt.error().kind, ErrorKind::InvalidInput) << corrupt.error().message;
  const std::string name =
      std::to_string(under.front().z) + "/" + std::to_string(under.front().x) + "/" + std::to_string(under.front().y);
  EXPECT_NE(corrupt.error().message.find(name), std::string::npos) << corrupt.error().message;
}

TEST(PlantsInBox, MistakesAreErrorsNamingTheBoxTheLimitOrTheDataset) {
  const fs::path dir = ownTestDir();
  const fs::path dataset = makeDataset(dir);
  const auto& catalog = vegetation::defaultSpeciesCatalog();
  PlantsInBoxOptions o;
  o.boxName = "BOX";
  o.maxPlantsName = "LIMIT";
  const auto outside = plantsInBox(dataset.string(), boxAround(kLat + 1.0, kLon, 10.0), catalog, o);
  ASSERT_FALSE(outside.ok());
  EXPECT_EQ(outside.error().kind, ErrorKind::InvalidInput);
  EXPECT_EQ(outside.error().message.rfind("BOX: not inside the dataset's bounds", 0), 0u) << outside.error().message;

  o.maxPlants = 1000;  // a 20 m box grows tens of thousands
  const auto many = plantsInBox(dataset.string(), boxAround(kLat, kLon, 10.0), catalog, o);
  ASSERT_FALSE(many.ok());
  EXPECT_NE(many.error().message.find("grows"), std::string::npos) << many.error().message;
  EXPECT_NE(many.error().message.find("more than LIMIT 1000"), std::string::npos) << many.error().message;

  const auto missing = plantsInBox((dir / "nowhere").string(), boxAround(kLat, kLon, 10.0), catalog, {});
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.error().kind, ErrorKind::NotFound) << missing.error().message;

  // The same dataset without imagery: species come from its colour, so none can be chosen.
  nlohmann::json j = nlohmann::json::parse(std::ifstream(dataset / "dataset.json"));
  j["imagery"] = nullptr;
  std::ofstream(dataset / "dataset.json") << j.dump(2);
  const auto bare = plantsInBox(dataset.string(), boxAround(kLat, kLon, 10.0), catalog, {});
  ASSERT_FALSE(bare.ok());
  EXPECT_NE(bare.error().message.find("imagery"), std::string::npos) << bare.error().message;
}

}  // namespace
}  // namespace vegstream::scene
