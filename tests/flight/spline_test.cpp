// The two interpolants under flight paths: centripetal Catmull-Rom (Yuksel et al. 2011) passes
// through its points, is C¹, and has no loop or cusp at a sharp turn with uneven spacing where
// the uniform parameterisation loops; the monotone cubic (Fritsch–Carlson) never overshoots.

#include <cmath>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "flight/catmull_rom.h"
#include "flight/monotone_cubic.h"

namespace vegstream::flight {
namespace {

// Whether segments ab and cd cross (proper intersection, 2D in x/y).
bool crosses(glm::dvec3 a, glm::dvec3 b, glm::dvec3 c, glm::dvec3 d) {
  auto side = [](glm::dvec3 p, glm::dvec3 q, glm::dvec3 r) {
    return (q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x);
  };
  return side(a, b, c) * side(a, b, d) < 0.0 && side(c, d, a) * side(c, d, b) < 0.0;
}

int selfIntersections(const CentripetalCatmullRom& cr) {
  std::vector<glm::dvec3> poly;
  const double end = cr.knot(cr.size() - 1);
  for (int i = 0; i <= 2000; ++i) poly.push_back(cr.position(end * i / 2000.0));
  int count = 0;
  for (std::size_t i = 0; i + 1 < poly.size(); ++i)
    for (std::size_t j = i + 2; j + 1 < poly.size(); ++j)
      if (crosses(poly[i], poly[i + 1], poly[j], poly[j + 1])) ++count;
  return count;
}

// A sharp V with a short bottom: two 70 m legs joined by a 2 m step.
const std::vector<glm::dvec3> kHairpin = {{-50, 50, 0}, {0, 0, 0}, {2, 0, 0}, {52, 50, 0}};

TEST(CatmullRom, PassesThroughItsPointsAtItsKnots) {
  const std::vector<glm::dvec3> pts = {{0, 0, 0}, {10, 5, 1}, {11, 30, 2}, {50, 31, 0}, {52, 33, 5}};
  const CentripetalCatmullRom cr(pts);
  for (std::size_t i = 0; i < pts.size(); ++i) EXPECT_LT(glm::length(cr.position(cr.knot(i)) - pts[i]), 1e-12);
  // Knots are spaced by the square root of the chord length.
  EXPECT_NEAR(cr.knot(1) - cr.knot(0), std::sqrt(glm::length(pts[1] - pts[0])), 1e-12);
}

TEST(CatmullRom, DerivativeIsContinuousAtEveryPoint) {
  const std::vector<glm::dvec3> pts = {{0, 0, 0}, {10, 5, 1}, {11, 30, 2}, {50, 31, 0}, {52, 33, 5}};
  const CentripetalCatmullRom cr(pts);
  for (std::size_t i = 1; i + 1 < pts.size(); ++i) {
    const double s = cr.knot(i), h = 1e-6;
    const glm::dvec3 left = (cr.position(s) - cr.position(s - h)) / h;
    const glm::dvec3 right = (cr.position(s + h) - cr.position(s)) / h;
    EXPECT_LT(glm::length(left - right), 1e-3 * glm::length(left)) << "at point " << i;
    EXPECT_LT(glm::length(cr.derivative(s) - left), 1e-3 * glm::length(left));
  }
}

TEST(CatmullRom, CentripetalHasNoLoopAtASharpTurnWhereUniformLoops) {
  const CentripetalCatmullRom centripetal(kHairpin, 0.5);
  const CentripetalCatmullRom uniform(kHairpin, 0.0);
  EXPECT_EQ(selfIntersections(centripetal), 0);
  EXPECT_GT(selfIntersections(uniform), 0) << "the test must be able to see a loop";
  // No cusp: the speed along the curve never drops to zero, and the turn bulges only a little
  // below the corner.
  double minSpeed = INFINITY, minY = 0.0;
  const double end = centripetal.knot(3);
  for (int i = 0; i <= 3000; ++i) {
    const double s = end * i / 3000.0;
    minSpeed = std::min(minSpeed, glm::length(centripetal.derivative(s)));
    minY = std::min(minY, centripetal.position(s).y);
  }
  EXPECT_GT(minSpeed, 0.1);
  EXPECT_GT(minY, -2.0);
}

TEST(MonotoneCubic, InterpolatesWithoutOvershoot) {
  // A dive to 15 m that stays there, then a climb: the curve never goes below 15.
  const MonotoneCubic m({0, 5, 10, 15, 20, 25, 30}, {1800, 600, 15, 15, 15, 600, 1800});
  EXPECT_DOUBLE_EQ(m.value(10.0), 15.0);
  for (int i = 0; i <= 3000; ++i) {
    const double x = 30.0 * i / 3000.0;
    EXPECT_GE(m.value(x), 15.0 - 1e-9) << x;
    EXPECT_LE(m.value(x), 1800.0 + 1e-9) << x;
    if (x >= 10.0 && x <= 20.0) {
      EXPECT_NEAR(m.value(x), 15.0, 1e-9);
    }
  }
  // C¹ at the samples.
  for (double x : {5.0, 25.0}) {
    const double h = 1e-6;
    EXPECT_NEAR((m.value(x) - m.value(x - h)) / h, (m.value(x + h) - m.value(x)) / h, 1e-2);
  }
  // Clamped outside the range.
  EXPECT_DOUBLE_EQ(m.value(-1.0), 1800.0);
  EXPECT_DOUBLE_EQ(m.value(99.0), 1800.0);
}

}  // namespace
}  // namespace vegstream::flight
