// Wedgie culling (terrain/eye_space.h): the prism test against its six corners tested plane by
// plane, and the plane masks that hierarchical culling hands down a nested subtree.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

#include <glm/geometric.hpp>

#include "terrain/eye_space.h"

namespace vegstream::terrain {
namespace {

// A view in eye space (the tests give eye coordinates): only the frustum and the up direction
// enter the culling.
EyeView viewWithUp(const glm::dvec3& upEye) {
  EyeView v;
  v.tanHalfX = 1.2;
  v.tanHalfY = 0.7;
  v.nearM = 0.5;
  v.upEye = glm::normalize(upEye);
  return v;
}

// The planes written out (n·q + d ≥ 0 inside): what Frustum's coefficients stand for.
double planeDistance(const EyeView& view, const glm::dvec3& q, int k) {
  switch (k) {
    case 0: return -q.z - view.nearM;
    case 1: return q.x - view.tanHalfX * q.z;
    case 2: return -q.x - view.tanHalfX * q.z;
    case 3: return q.y - view.tanHalfY * q.z;
    default: return -q.y - view.tanHalfY * q.z;
  }
}

// The reference: the prism's six corners v + s·up, s ∈ {−below, +above}, against each plane.
Cull byCorners(const EyeView& view, const std::array<glm::dvec3, 3>& tri, double below, double above) {
  bool inside = true;
  for (int k = 0; k < 5; ++k) {
    int out = 0;
    for (const glm::dvec3& v : tri)
      for (const double s : {-below, above}) out += planeDistance(view, v + s * view.upEye, k) < 0.0 ? 1 : 0;
    if (out == 6) return Cull::Outside;
    if (out > 0) inside = false;
  }
  return inside ? Cull::Inside : Cull::Partial;
}

struct Scene {
  std::mt19937 rng{20261204};
  glm::dvec3 point() {
    std::uniform_real_distribution<double> x(-60.0, 60.0), y(-40.0, 40.0), z(-90.0, 6.0);
    return {x(rng), y(rng), z(rng)};
  }
  double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); }
  // Triangles of 1–40 m about a point of the box: wholly in, wholly out and straddling.
  std::array<glm::dvec3, 3> triangle() {
    const glm::dvec3 c = point();
    const double r = uniform(1.0, 40.0);
    auto corner = [&] { return c + glm::dvec3(uniform(-r, r), uniform(-r, r), uniform(-r, r)); };
    return {corner(), corner(), corner()};
  }
};

TEST(WedgieCulling, TheFrustumsCoefficientsGiveThePlanesDistancesExactly) {
  Scene s;
  for (int i = 0; i < 2000; ++i) {
    const EyeView view = viewWithUp({s.uniform(-0.3, 0.3), 1.0, s.uniform(-0.3, 0.3)});
    const Frustum f(view);
    const glm::dvec3 q = s.point();
    for (int k = 0; k < 5; ++k) {
      // Bit for bit: the culling of a chunk's triangles one by one must agree with the traversal's.
      ASSERT_EQ(f.distance(q, k), planeDistance(view, q, k)) << "plane " << k << ", point " << i;
      ASSERT_EQ(f.up[k], k == 0 ? -view.upEye.z : planeDistance(view, view.upEye, k)) << "plane " << k;
    }
  }
}

TEST(WedgieCulling, EveryPlaneAgreesWithThePrismsCornersAndTheMaskSaysWhichAreStraddled) {
  Scene s;
  int seen[3] = {0, 0, 0};
  for (int i = 0; i < 20000; ++i) {
    const EyeView view = viewWithUp({s.uniform(-0.3, 0.3), 1.0, s.uniform(-0.3, 0.3)});
    const std::array<glm::dvec3, 3> tri = s.triangle();
    const double below = s.uniform(0.0, 8.0), above = below + s.uniform(0.0, 30.0);
    const Cull expected = byCorners(view, tri, below, above);
    PlaneMask planes = kEveryPlane;
    const Cull got = cullWedgie(Frustum(view), tri[0], tri[1], tri[2], below, above, planes);
    ASSERT_EQ(got, expected) << "triangle " << i;
    ASSERT_EQ(cullWedgie(view, tri[0], tri[1], tri[2], below, above), expected);
    ++seen[int(got)];
    if (got == Cull::Outside) continue;
    // The mask holds exactly the planes some corner is outside of.
    for (int k = 0; k < 5; ++k) {
      bool someOut = false;
      for (const glm::dvec3& v : tri)
        for (const double h : {-below, above}) someOut = someOut || planeDistance(view, v + h * view.upEye, k) < 0.0;
      ASSERT_EQ((planes >> k) & 1u, someOut ? 1u : 0u) << "plane " << k << ", triangle " << i;
    }
  }
  for (int c = 0; c < 3; ++c) EXPECT_GT(seen[c], 1000) << "outcome " << c;
}

TEST(WedgieCulling, ANestedWedgieTestedAgainstItsParentsStraddledPlanesGetsWhatEveryPlaneGives) {
  // A child of a bintree triangle: two of its vertices (apex, left), and the midpoint of its
  // base moved along up by δ, with a thickness e such that |δ| + e ≤ E — its prism lies in the
  // parent's (what the nested thicknesses guarantee, roam_mesh.h).
  Scene s;
  int partialParents = 0, childOutcomes[3] = {0, 0, 0};
  for (int i = 0; i < 20000; ++i) {
    const EyeView view = viewWithUp({s.uniform(-0.3, 0.3), 1.0, s.uniform(-0.3, 0.3)});
    const auto [a, b, c] = s.triangle();
    const double E = s.uniform(0.0, 8.0), canopy = s.uniform(0.0, 30.0);
    PlaneMask parentPlanes = kEveryPlane;
    const Cull parent = cullWedgie(Frustum(view), a, b, c, E, E + canopy, parentPlanes);
    const double delta = s.uniform(-E, E), e = s.uniform(0.0, E - std::abs(delta));
    const glm::dvec3 m = 0.5 * (b + c) + delta * view.upEye;
    const Cull full = cullWedgie(view, m, a, b, e, e + canopy);
    if (parent != Cull::Partial) {
      ASSERT_EQ(full, parent) << "a child of a wholly inside or outside wedgie is the same, triangle " << i;
      continue;
    }
    ++partialParents;
    PlaneMask childPlanes = parentPlanes;
    const Cull masked = cullWedgie(Frustum(view), m, a, b, e, e + canopy, childPlanes);
    ASSERT_EQ(masked, full) << "triangle " << i;
    ASSERT_EQ(childPlanes & ~parentPlanes, 0) << "a child straddles only planes its parent straddles";
    ++childOutcomes[int(masked)];
  }
  EXPECT_GT(partialParents, 5000);
  for (int c = 0; c < 3; ++c) EXPECT_GT(childOutcomes[c], 300) << "outcome " << c;
}

}  // namespace
}  // namespace vegstream::terrain
