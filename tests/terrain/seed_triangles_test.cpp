// Seed triangles (seed 001 §2.1, §3.1): view-independent identity and vertices, coverage of the
// visible ground within the horizon, and eq. 1 / eq. 2 against hand computations.

#include <cmath>
#include <map>
#include <random>
#include <set>

#include <gtest/gtest.h>

#include "terrain/seed_triangles.h"
#include "tests/terrain/roam_fixture.h"

namespace vegstream::terrain {
namespace {

using test::zionResident;

bool contains(const BintreeGrid& g, const TriCorners& t, glm::dvec2 p) {
  auto xy = [&](GridPoint q) { return glm::dvec2(double(q.x), double(q.y)); };
  const glm::dvec2 a = xy(t.apex), b = xy(t.left), c = xy(t.right);
  auto side = [&](glm::dvec2 u, glm::dvec2 v) { return (v.x - u.x) * (p.y - u.y) - (v.y - u.y) * (p.x - u.x); };
  const double s0 = side(a, b), s1 = side(b, c), s2 = side(c, a);
  (void)g;
  return (s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0);
}

// The path of the level-`level` triangle containing grid point p (grid-zoom units).
TriPath pathAt(const BintreeGrid& g, glm::dvec2 p, int level) {
  const double scale = std::ldexp(1.0, g.rootZoom() - g.gridZoom());
  TriPath path{int32_t(std::floor(p.x * scale)), int32_t(std::floor(p.y * scale)), 0, 0, 0};
  TriCorners t = g.rootCorners(path.rootX, path.rootY, 0);
  if (!contains(g, t, p)) {
    path.tree = 1;
    t = g.rootCorners(path.rootX, path.rootY, 1);
  }
  for (int l = 0; l < level; ++l) {
    const int which = contains(g, child(t, 0), p) ? 0 : 1;
    t = child(t, which);
    path = childPath(path, which);
  }
  return path;
}

TEST(SeedTriangles, SameGroundSameTriangleFromAnyCameraAndTheyCoverTheVisibleGround) {
  auto& z = zionResident();
  const PieceSet pieces = z.finestPieces();
  SeedOptions so;
  so.horizonM = 150.0;
  auto r = z.tessellator({}, so);
  std::mt19937 rng(2026);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::map<TriPath, std::array<glm::dvec3, 3>> seen;
  uint64_t repeats = 0, total = 0, covered = 0, probes = 0, interpolated = 0;
  const geo::GeoBounds& b = z.meta().bounds;
  // Ten places, ten cameras each within 80 m of it, any heading, 10 … 90 m up, looking down.
  double lat = 0.0, lon = 0.0;
  for (int cam = 0; cam < 100; ++cam) {
    if (cam % 10 == 0) {
      lat = b.southDeg + (0.2 + 0.6 * u(rng)) * (b.northDeg - b.southDeg);
      lon = b.westDeg + (0.2 + 0.6 * u(rng)) * (b.eastDeg - b.westDeg);
    }
    const double dLat = (u(rng) - 0.5) * 160.0 / 111000.0, dLon = (u(rng) - 0.5) * 160.0 / 88000.0;
    const EyeView view =
        z.camera(lat + dLat, lon + dLon, 10.0 + 80.0 * u(rng), 360.0 * u(rng), -15.0 - 30.0 * u(rng), 320.0, 180.0);
    test::converge(*r, view, pieces, 30);
    std::vector<TerrainMesh> meshes;
    std::vector<SeedTriangle> seeds;
    r->output(view, pieces, 0.0, meshes, seeds);
    std::set<TriPath> here;
    for (const SeedTriangle& s : seeds) {
      ASSERT_EQ(s.path.level, r->seedLevel());
      here.insert(s.path);
      interpolated += s.interpolated;
      auto [it, fresh] = seen.try_emplace(s.path, s.world);
      if (!fresh) {
        ++repeats;
        for (int k = 0; k < 3; ++k) ASSERT_EQ(it->second[size_t(k)], s.world[size_t(k)]) << "camera " << cam;
      }
      // The vertices are those of the path, on the ground; its corners are the path's (the
      // output hands them down instead of walking the path).
      const TriCorners c = z.grid().corners(s.path);
      ASSERT_EQ(s.corners, c) << "camera " << cam;
      const GridPoint pts[3] = {c.apex, c.left, c.right};
      for (int k = 0; k < 3; ++k) {
        const HeightSample h = z.heights().sample(pts[k]);
        const glm::dvec2 ll = geo::tileXYToLonLat(z.grid().tileXY(pts[k], z.grid().gridZoom()), z.grid().gridZoom());
        ASSERT_LT(glm::length(z.frame().toLocal({ll.y, ll.x, h.heightM}) - s.world[size_t(k)]), 1e-3);
      }
    }
    total += seeds.size();
    // Coverage: random ground points within the horizon whose seed triangle is in view, faces
    // the camera and has its nearest vertex within the horizon must have been emitted.
    for (int k = 0; k < 200; ++k) {
      const double a = 2.0 * M_PI * u(rng), d = so.horizonM * std::sqrt(u(rng));
      const geo::Geodetic g = z.frame().toGeodetic(view.cameraEnu + glm::dvec3(d * std::cos(a), d * std::sin(a), 0.0));
      const glm::dvec2 xy = geo::lonLatToTileXY({g.lonDeg, g.latDeg}, z.grid().gridZoom());
      const TriPath p = pathAt(z.grid(), xy, r->seedLevel());
      const TriCorners c = z.grid().corners(p);
      glm::dvec3 eye[3];
      double nearest = 1e30;
      bool data = true;
      const GridPoint pts[3] = {c.apex, c.left, c.right};
      for (int i = 0; i < 3; ++i) {
        const HeightSample h = z.heights().sample(pts[i]);
        data = data && h.heightM == h.heightM;
        const glm::dvec2 ll = geo::tileXYToLonLat(z.grid().tileXY(pts[i], z.grid().gridZoom()), z.grid().gridZoom());
        eye[i] = view.toEye(z.frame().toLocal({ll.y, ll.x, h.heightM}));
        nearest = std::min(nearest, glm::length(eye[i]));
      }
      if (!data || nearest > so.horizonM) continue;
      if (glm::dot(glm::cross(eye[1] - eye[0], eye[2] - eye[0]), eye[0]) > 0.0) continue;
      if (cullWedgie(view, eye[0], eye[1], eye[2], 0.0, 0.0) != Cull::Inside) continue;
      ++probes;
      covered += here.count(p);
    }
  }
  EXPECT_GT(total, 5000u);
  EXPECT_GT(repeats, 500u) << "cameras overlap enough to compare";
  EXPECT_EQ(interpolated, 0u) << "ROAM reached the seed level inside the horizon";
  EXPECT_GT(probes, 1000u);
  EXPECT_EQ(covered, probes);
}

// A camera at the origin looking down −z, 1000 px per radian (fovY = 2·atan(0.54), 1080 px).
EyeView handView() {
  EyeView v = EyeView::lookAlong({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 2.0 * std::atan(0.54), 1920.0, 1080.0, 1.0);
  return v;
}

TEST(SeedTriangles, Eq1AgainstHandComputation) {
  const EyeView v = handView();
  ASSERT_NEAR(v.pixelsPerRadian, 1000.0, 1e-9);
  SeedOptions o;
  o.density = 0.01;
  o.maxPlants = 256.0;
  // Legs of 1 m at 10 m: projected legs 100 px, area 5000 px², ρ A = 50.
  const std::array<glm::dvec3, 3> t{{{0, 0, -10}, {1, 0, -10}, {0, 1, -10}}};
  EXPECT_NEAR(screenAreaPx(v, t[0], t[1], t[2]), 5000.0, 1e-9);
  bool nearPlane = true;
  EXPECT_NEAR(plantCountScreen(v, t, o, &nearPlane), 50.0, 1e-9);
  EXPECT_FALSE(nearPlane);
  // At 2 m the area is 25 × larger: 1250 plants, clamped to n_max.
  const std::array<glm::dvec3, 3> close{{{0, 0, -2}, {1, 0, -2}, {0, 1, -2}}};
  EXPECT_NEAR(plantCountScreen(v, close, o), 256.0, 1e-9);
  // A vertex behind the near plane (1 m): n_max without projecting.
  const std::array<glm::dvec3, 3> crossing{{{0, 0, -0.5}, {1, 0, -10}, {0, 1, -10}}};
  EXPECT_EQ(plantCountScreen(v, crossing, o, &nearPlane), 256.0);
  EXPECT_TRUE(nearPlane);
}

// Belyaev's contour term (seed 004 §2.2): 1 where the ground faces the camera, growing as it turns
// edge-on, and off with α = 0; applied to eq. 1 it multiplies the count by the same factor.
TEST(SeedTriangles, TheContourTermKeepsGrazingGroundDense) {
  EXPECT_DOUBLE_EQ(contourFactor(1.0, 8.0), 1.0);
  EXPECT_DOUBLE_EQ(contourFactor(0.3, 0.0), 1.0);
  // c = 0.057 (1.7 m up, 30 m out): t = 0.943^8 = 0.625; ((1 − t) c + t) / c = 11.3.
  const double t = std::pow(1.0 - 0.057, 8.0);
  EXPECT_NEAR(contourFactor(0.057, 8.0), ((1.0 - t) * 0.057 + t) / 0.057, 1e-12);
  EXPECT_NEAR(contourFactor(0.057, 8.0), 11.3, 0.05);
  EXPECT_NEAR(contourFactor(-0.057, 8.0), contourFactor(0.057, 8.0), 1e-12) << "either side";
  double last = 1.0;
  for (double c = 0.95; c > 0.01; c -= 0.05) {
    EXPECT_GT(contourFactor(c, 8.0), last) << c;
    last = contourFactor(c, 8.0);
  }
  EXPECT_TRUE(std::isfinite(contourFactor(0.0, 8.0)));
  // Eq. 1 on a ground triangle seen at a grazing angle: the count times the factor of its cosine.
  const EyeView v = handView();
  SeedOptions o;
  o.density = 0.01;
  o.maxPlants = 1e9;
  const std::array<glm::dvec3, 3> grazing{{{0, -2, -20}, {1, -2, -20}, {0, -2, -22}}};  // level ground, 2 m below
  const double plain = plantCountScreen(v, grazing, o);
  o.contourAlpha = 8.0;
  const glm::dvec3 centre = (grazing[0] + grazing[1] + grazing[2]) / 3.0;
  const double cosine = 2.0 / glm::length(centre);
  EXPECT_NEAR(plantCountScreen(v, grazing, o), plain * contourFactor(cosine, 8.0), 1e-6 * plain);
  EXPECT_GT(plantCountScreen(v, grazing, o), 5.0 * plain);
}

TEST(SeedTriangles, TheLevelOfDetailIsTheSameAtAnyWindowSizeAndTheGroundCapsIt) {
  // ρ counts pixels of a 1080-line view: the same view in a 320×180 window grows the same plants
  // (issue 18: the count "does not depend on the window's resolution").
  const EyeView big = handView();
  const EyeView small =
      EyeView::lookAlong({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 2.0 * std::atan(0.54), 320.0, 180.0, 1.0);
  SeedOptions o;
  o.density = 0.01;
  o.maxPlants = 1e6;
  const std::array<glm::dvec3, 3> t{{{0, 0, -10}, {1, 0, -10}, {0, 1, -10}}};
  EXPECT_NEAR(plantCountScreen(small, t, o), plantCountScreen(big, t, o), 1e-9);
  EXPECT_NEAR(plantCountWorld(small, t, o), plantCountWorld(big, t, o), 1e-9);
  // Near the camera the ground decides: N = min(lodCount, D · A) · horizon fade.
  o.groundDensityM2 = 400.0;
  o.horizonM = 100.0;
  EXPECT_NEAR(groundArea(t), 0.5, 1e-12);
  EXPECT_NEAR(groundPlantCount(50.0, 0.5, 5.0, o), 50.0, 1e-12);      // the level of detail
  EXPECT_NEAR(groundPlantCount(5000.0, 0.5, 5.0, o), 200.0, 1e-12);   // the ground
  EXPECT_NEAR(groundPlantCount(5000.0, 0.5, 87.5, o), 100.0, 1e-12);  // half way through the fade
  EXPECT_EQ(groundPlantCount(5000.0, 0.5, 100.0, o), 0.0);
}

TEST(SeedTriangles, Eq2AgainstHandComputation) {
  const EyeView v = handView();
  SeedOptions o;
  o.density = 0.01;
  o.maxPlants = 256.0;
  const std::array<glm::dvec3, 3> t{{{0, 0, -10}, {1, 0, -10}, {0, 1, -10}}};
  // A_w = 0.5, n̂ = (0, 0, 1), v = (1/3, 1/3, −10): ‖v‖² = 100 + 2/9, n̂·v/‖v‖ = 10/‖v‖.
  const double v2 = 100.0 + 2.0 / 9.0;
  const double expected = 0.01 * 0.5 * (10.0 / std::sqrt(v2)) / v2 * 1000.0 * 1000.0;
  EXPECT_NEAR(plantCountWorld(v, t, o), expected, 1e-9);
  EXPECT_NEAR(expected, 49.834, 0.001);  // close to eq. 1's 50 near the view centre
  // Seen edge-on the count goes to 0; very close it clamps.
  const std::array<glm::dvec3, 3> edgeOn{{{0, 0, -10}, {1, 0, -10}, {0, 0, -11}}};
  EXPECT_NEAR(plantCountWorld(v, edgeOn, o), 0.0, 1e-12);  // the view ray lies in its plane
  const std::array<glm::dvec3, 3> close{{{0, 0, -1}, {1, 0, -1}, {0, 1, -1}}};
  EXPECT_EQ(plantCountWorld(v, close, o), 256.0);
}

TEST(SeedTriangles, PlantCountsFadeOutBeforeTheHorizon) {
  // Issue 18's popping at the seeding horizon: the count's factor is 1 up to ¾ of the horizon,
  // 0 at it, continuous and non-increasing between (so a triangle's plants leave one by one as
  // the camera moves away, none at the cut), changing by at most 1.5 cm / (¼ horizon) per
  // centimetre travelled.
  const double h = 250.0;
  EXPECT_EQ(horizonFade(0.0, h), 1.0);
  EXPECT_EQ(horizonFade(0.75 * h, h), 1.0);
  EXPECT_EQ(horizonFade(h, h), 0.0);
  EXPECT_EQ(horizonFade(2.0 * h, h), 0.0);
  EXPECT_NEAR(horizonFade(0.875 * h, h), 0.5, 1e-12);
  double previous = 1.0, steepest = 0.0;
  for (double d = 0.0; d <= h + 1.0; d += 0.01) {
    const double f = horizonFade(d, h);
    EXPECT_LE(f, previous);
    steepest = std::max(steepest, previous - f);
    previous = f;
  }
  // The steepest step of a smoothstep over 62.5 m, per centimetre: 1.5 × 0.01 / 62.5.
  EXPECT_LT(steepest, 0.01 * 1.5 / (0.25 * h) + 1e-9);
}

TEST(SeedTriangles, SeedLevelFollowsTheTargetArea) {
  const BintreeGrid g(8, 14);
  const int l = seedLevelFor(g, 37.3, 24.0);
  EXPECT_GT(triangleAreaM2(g, l, 37.3), 24.0 / std::sqrt(2.0) - 1e-9);
  EXPECT_LT(triangleAreaM2(g, l, 37.3), 24.0 * std::sqrt(2.0) + 1e-9);
  EXPECT_NEAR(triangleAreaM2(g, l, 37.3) / triangleAreaM2(g, l + 1, 37.3), 2.0, 1e-12);
}

}  // namespace
}  // namespace vegstream::terrain
