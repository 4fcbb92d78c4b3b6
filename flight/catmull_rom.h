#pragma once
// Centripetal Catmull-Rom spline through control points (alpha = 0.5): Yuksel, Schaefer &
// Keyser, "Parameterization and applications of Catmull-Rom curves", Computer-Aided Design
// 43(7), 2011. With knots spaced by |P(i+1) − P(i)|^0.5 the curve has no cusps or
// self-intersections inside a segment and follows the control polygon tightly, also when the
// keyframes are spaced unevenly — which is why flights use it (DESIGN.md "Flight paths").
//
// Evaluated in Hermite form: the tangent at P(i) is the derivative of the Barry–Goldman
// pyramid there, which depends only on P(i−1), P(i), P(i+1) and their knots, so both segments
// meeting at P(i) share it and the curve is C¹ in its knot parameter s. The end segments use
// reflected phantom points P(−1) = 2P(0) − P(1), P(n) = 2P(n−1) − P(n−2).

#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

namespace vegstream::flight {

class CentripetalCatmullRom {
 public:
  // points.size() >= 2 (asserted). Coincident neighbours get a tiny knot step (1e-6) so the
  // spline stays defined: the curve rests there.
  explicit CentripetalCatmullRom(std::vector<glm::dvec3> points, double alpha = 0.5);

  std::size_t size() const { return points_.size(); }
  // s of control point i: knot(0) = 0, knot(i + 1) = knot(i) + |P(i+1) − P(i)|^alpha.
  double knot(std::size_t i) const { return knots_[i]; }
  const std::vector<double>& knots() const { return knots_; }

  // Position and dP/ds at s, clamped to [knot(0), knot(n−1)].
  glm::dvec3 position(double s) const;
  glm::dvec3 derivative(double s) const;

 private:
  std::size_t segment(double s) const;

  std::vector<glm::dvec3> points_;
  std::vector<double> knots_;
  std::vector<glm::dvec3> tangents_;  // dP/ds at each control point
};

}  // namespace vegstream::flight
