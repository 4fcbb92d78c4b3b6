#include "flight/catmull_rom.h"
#include "flight/cubic_hermite.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include <glm/geometric.hpp>

namespace vegstream::flight {
namespace {

constexpr double kMinKnotStep = 1e-6;

// dP/ds at P1 of the Barry–Goldman pyramid over P0, P1, P2 with knots s0 < s1 < s2.
glm::dvec3 tangentAt(const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& p2, double s0, double s1,
                     double s2) {
  return (p1 - p0) / (s1 - s0) - (p2 - p0) / (s2 - s0) + (p2 - p1) / (s2 - s1);
}

}  // namespace

CentripetalCatmullRom::CentripetalCatmullRom(std::vector<glm::dvec3> points, double alpha)
    : points_(std::move(points)) {
  assert(points_.size() >= 2);
  const std::size_t n = points_.size();
  knots_.resize(n);
  knots_[0] = 0.0;
  for (std::size_t i = 1; i < n; ++i)
    knots_[i] = knots_[i - 1] + std::max(std::pow(glm::length(points_[i] - points_[i - 1]), alpha), kMinKnotStep);

  tangents_.resize(n);
  // Phantom points mirror the neighbour, so their knot step equals the first/last step.
  const glm::dvec3 before = 2.0 * points_[0] - points_[1];
  const glm::dvec3 after = 2.0 * points_[n - 1] - points_[n - 2];
  const double stepFirst = knots_[1] - knots_[0];
  const double stepLast = knots_[n - 1] - knots_[n - 2];
  for (std::size_t i = 0; i < n; ++i) {
    const glm::dvec3& prev = i == 0 ? before : points_[i - 1];
    const glm::dvec3& next = i + 1 == n ? after : points_[i + 1];
    const double sPrev = i == 0 ? -stepFirst : knots_[i - 1];
    const double sNext = i + 1 == n ? knots_[i] + stepLast : knots_[i + 1];
    tangents_[i] = tangentAt(prev, points_[i], next, sPrev, knots_[i], sNext);
  }
}

std::size_t CentripetalCatmullRom::segment(double s) const { return hermiteSegment(knots_, s); }

glm::dvec3 CentripetalCatmullRom::position(double s) const {
  s = std::clamp(s, knots_.front(), knots_.back());
  const std::size_t i = segment(s);
  const double h = knots_[i + 1] - knots_[i];
  return hermiteValue(points_[i], tangents_[i], points_[i + 1], tangents_[i + 1], h, (s - knots_[i]) / h);
}

glm::dvec3 CentripetalCatmullRom::derivative(double s) const {
  s = std::clamp(s, knots_.front(), knots_.back());
  const std::size_t i = segment(s);
  const double h = knots_[i + 1] - knots_[i];
  return hermiteDerivative(points_[i], tangents_[i], points_[i + 1], tangents_[i + 1], h, (s - knots_[i]) / h);
}

}  // namespace vegstream::flight
