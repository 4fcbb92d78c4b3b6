// Seed triangles of a box without a camera (terrain/seed_region.h) against the ROAM tessellator
// from two cameras: the same paths and bit-identical vertices, hence the same plants (core seed
// ../shared/seeds/001_3eca9f2c7752e4fb.txt §2.2: a plant depends only on its triangle and its
// index); and zooming in only appends plants to each triangle's sequence (DESIGN.md invariant).

#include <cmath>
#include <map>
#include <set>

#include <gtest/gtest.h>

#include "terrain/seed_region.h"
#include "terrain/seed_triangles.h"
#include "tests/terrain/roam_fixture.h"
#include "vegetation/colour_score.h"
#include "vegetation/plant_seeding.h"

namespace vegstream::terrain {
namespace {

namespace veg = vegetation;
using test::zionResident;

constexpr double kMPerDegLat = 111000.0;

// A 60 m × 60 m box around (lat, lon).
geo::GeoBounds boxAround(double lat, double lon, double halfM) {
  const double dLat = halfM / kMPerDegLat, dLon = halfM / (kMPerDegLat * std::cos(lat * M_PI / 180.0));
  return {lon - dLon, lat - dLat, lon + dLon, lat + dLat};
}

// A camera `aboveM` over the ground `backM` from (lat, lon) towards `bearingDeg`, looking at the
// ground at (lat, lon).
EyeView cameraLookingAt(test::ZionResident& z, double lat, double lon, double bearingDeg, double backM, double aboveM) {
  const double b = bearingDeg * M_PI / 180.0;
  const double cLat = lat + backM * std::cos(b) / kMPerDegLat;
  const double cLon = lon + backM * std::sin(b) / (kMPerDegLat * std::cos(lat * M_PI / 180.0));
  const double ground = z.heights().sampleLonLat(cLat, cLon).heightM;
  const glm::dvec3 eye = z.frame().toLocal({cLat, cLon, ground + aboveM});
  const glm::dvec3 target = z.frame().toLocal({lat, lon, z.heights().sampleLonLat(lat, lon).heightM});
  return EyeView::lookAlong(eye, glm::normalize(target - eye), {0.0, 0.0, 1.0}, M_PI / 3.0, 1920.0, 1080.0, 1.0);
}

bool centroidIn(const BintreeGrid& g, const TriCorners& t, const geo::GeoBounds& box) {
  const glm::dvec2 c =
      (g.tileXY(t.apex, g.gridZoom()) + g.tileXY(t.left, g.gridZoom()) + g.tileXY(t.right, g.gridZoom())) / 3.0;
  const glm::dvec2 ll = geo::tileXYToLonLat(c, g.gridZoom());
  return ll.x >= box.westDeg && ll.x < box.eastDeg && ll.y > box.southDeg && ll.y <= box.northDeg;
}

// The seed triangles a converged tessellator emits for `view` whose centroid is in the box.
std::map<TriPath, SeedTriangle> roamSeedsIn(test::ZionResident& z, const EyeView& view, const geo::GeoBounds& box) {
  const PieceSet pieces = z.finestPieces();
  auto r = z.tessellator();
  test::converge(*r, view, pieces, 200);
  std::vector<TerrainMesh> meshes;
  std::vector<SeedTriangle> seeds;
  r->output(view, pieces, 0.0, meshes, seeds);
  std::map<TriPath, SeedTriangle> in;
  for (const SeedTriangle& s : seeds)
    if (centroidIn(z.grid(), s.corners, box)) in.emplace(s.path, s);
  return in;
}

struct Grown {
  std::vector<veg::PlantCluster> clusters;
  std::vector<veg::Plant> plants;
};

// A synthetic base colour: meadow green west of x = splitX, red rock east of it (linear RGB).
Grown grow(const veg::SeedTriangleInput& t, double splitX) {
  const veg::BaseColourAt colour = [&](glm::vec2 r) {
    const glm::dvec3 p = veg::pointOnTriangle(t.vertices[0], t.vertices[1], t.vertices[2], r);
    return p.x < splitX ? glm::vec3(0.045f, 0.075f, 0.025f) : glm::vec3(0.30f, 0.12f, 0.08f);
  };
  Grown g;
  const veg::SpeciesCatalog& catalog = veg::defaultSpeciesCatalog();
  veg::classifyTriangle(t, 0, catalog, {8}, colour, g.clusters);
  veg::growPlants(t, g.clusters, catalog, {8}, g.plants);
  return g;
}

void expectSamePlant(const veg::Plant& a, const veg::Plant& b, const std::string& what) {
  EXPECT_EQ(a.cluster, b.cluster) << what;
  EXPECT_EQ(a.seed, b.seed) << what;
  EXPECT_EQ(a.position, b.position) << what;
  EXPECT_EQ(a.species, b.species) << what;
  EXPECT_EQ(a.heightM, b.heightM) << what;
  EXPECT_EQ(a.stiffness, b.stiffness) << what;
}

TEST(SeedRegion, SameTrianglesAndPlantsAsRoamFromAnyCameraAndZoomingInOnlyAddsPlants) {
  auto& z = zionResident();
  const glm::dvec2 c = z.meta().bounds.centre();
  const double lat = c.y + 0.1 * z.meta().bounds.heightDeg(), lon = c.x - 0.1 * z.meta().bounds.widthDeg();
  const geo::GeoBounds box = boxAround(lat, lon, 30.0);
  const int level = seedLevelFor(z.grid(), z.meta().bounds.centre().y, SeedOptions{}.targetAreaM2);
  const float nMax = 256.0f;  // full density, the same count for both triangles

  SeedRegionQuery q;
  q.box = box;
  q.seedLevel = level;
  q.densityM2 = 10.0;
  const SeedRegion region = seedTrianglesIn(z.grid(), z.roots(), z.frame(), z.heights(), q);
  ASSERT_EQ(region.nodataSkipped, 0u);
  // 3600 m² of triangles of about 24 m² (their area varies with the latitude of the root tiles).
  ASSERT_GT(region.triangles.size(), 100u);
  ASSERT_LT(region.triangles.size(), 300u);
  EXPECT_EQ(countSeedTrianglesIn(z.grid(), z.roots(), q), region.triangles.size());
  const double splitX = z.frame().toLocal({lat, lon, 0.0}).x;

  // Far: 150 m south, 60 m up; near: 70 m east, 20 m up. Both see the whole box within the horizon.
  const EyeView far = cameraLookingAt(z, lat, lon, 180.0, 150.0, 60.0);
  const EyeView near = cameraLookingAt(z, lat, lon, 90.0, 70.0, 20.0);
  const std::map<TriPath, SeedTriangle> fromFar = roamSeedsIn(z, far, box), fromNear = roamSeedsIn(z, near, box);

  std::set<uint32_t> species;
  uint64_t fullPlants = 0;
  for (const auto* seeds : {&fromFar, &fromNear}) {
    ASSERT_EQ(seeds->size(), region.triangles.size()) << "every triangle of the box, from either camera";
    for (const RegionSeedTriangle& s : region.triangles) {
      auto it = seeds->find(s.path);
      ASSERT_NE(it, seeds->end());
      const SeedTriangle& r = it->second;
      EXPECT_FALSE(r.interpolated);
      EXPECT_EQ(seedKey(r.path), s.key);
      for (size_t k = 0; k < 3; ++k) ASSERT_EQ(r.world[k], s.world[k]) << "bit-identical vertices";
      // Full density from the camera's triangle and from the region's: the same plants.
      const Grown a = grow({seedKey(r.path), r.world, nMax}, splitX), b = grow({s.key, s.world, nMax}, splitX);
      ASSERT_EQ(a.plants.size(), b.plants.size());
      for (size_t i = 0; i < a.plants.size(); ++i) expectSamePlant(a.plants[i], b.plants[i], "full density");
      for (const veg::Plant& p : b.plants) species.insert(p.species);
      fullPlants += b.plants.size();
    }
  }
  EXPECT_GE(species.size(), 2u) << "the synthetic colours pick different species";
  // Full density: ≈ n_max per triangle of ~24 m² (≈ 10 plants per m²), nothing bare here.
  EXPECT_GT(fullPlants, 2 * 200 * region.triangles.size());

  // Each camera's own counts (eq. 1): the far camera's plants are a prefix of the near one's.
  uint64_t farPlants = 0, nearPlants = 0, fewer = 0;
  for (const RegionSeedTriangle& s : region.triangles) {
    const SeedTriangle& f = fromFar.at(s.path);
    const SeedTriangle& n = fromNear.at(s.path);
    const Grown gf = grow({s.key, f.world, f.plantCount}, splitX), gn = grow({s.key, n.world, n.plantCount}, splitX);
    const Grown& small = f.plantCount <= n.plantCount ? gf : gn;
    const Grown& large = f.plantCount <= n.plantCount ? gn : gf;
    ASSERT_LE(small.plants.size(), large.plants.size());
    for (size_t i = 0; i < small.plants.size(); ++i) expectSamePlant(small.plants[i], large.plants[i], "prefix");
    fewer += f.plantCount < n.plantCount;
    farPlants += gf.plants.size();
    nearPlants += gn.plants.size();
  }
  EXPECT_GT(farPlants, 0u);
  EXPECT_GE(nearPlants, farPlants);
  EXPECT_GT(fewer, region.triangles.size() / 2) << "the far camera grows fewer plants on most triangles";
  std::printf("seed region: %zu triangles, %.1f plants per m² at full density; far %llu, near %llu plants\n",
              region.triangles.size(), double(fullPlants) / 2.0 / 3600.0, (unsigned long long)farPlants,
              (unsigned long long)nearPlants);
}

TEST(SeedRegion, AdjacentBoxesShareNoTriangleAndMissNone) {
  auto& z = zionResident();
  const glm::dvec2 c = z.meta().bounds.centre();
  const geo::GeoBounds whole = boxAround(c.y, c.x, 40.0);
  geo::GeoBounds west = whole, east = whole;
  west.eastDeg = east.westDeg = c.x;
  SeedRegionQuery q;
  q.seedLevel = seedLevelFor(z.grid(), c.y, SeedOptions{}.targetAreaM2);
  std::set<TriPath> all, halves;
  q.box = whole;
  for (const auto& s : seedTrianglesIn(z.grid(), z.roots(), z.frame(), z.heights(), q).triangles) all.insert(s.path);
  size_t n = 0;
  for (const geo::GeoBounds& b : {west, east}) {
    q.box = b;
    for (const auto& s : seedTrianglesIn(z.grid(), z.roots(), z.frame(), z.heights(), q).triangles) {
      halves.insert(s.path);
      ++n;
    }
  }
  EXPECT_GT(all.size(), 200u);
  EXPECT_EQ(n, all.size());
  EXPECT_EQ(halves, all);
  // Overlap keeps more: every triangle with ground in the box.
  q.box = whole;
  q.select = RegionSelect::Overlap;
  EXPECT_GT(countSeedTrianglesIn(z.grid(), z.roots(), q), all.size());
}

}  // namespace
}  // namespace vegstream::terrain
