#pragma once
// The cubic Hermite segment both path curves evaluate (centripetal Catmull–Rom, catmull_rom.h;
// Fritsch–Carlson monotone cubic, monotone_cubic.h): end values p0, p1, end slopes m0, m1 (per unit
// of the knot variable), knot spacing h, u ∈ [0, 1] the place within the segment. T is double or
// glm::dvec3. One expression for both, so the two curves round alike.

#include <algorithm>
#include <cstddef>
#include <vector>

namespace vegstream::flight {

template <class T>
T hermiteValue(const T& p0, const T& m0, const T& p1, const T& m1, double h, double u) {
  const double u2 = u * u, u3 = u2 * u;
  return (2 * u3 - 3 * u2 + 1) * p0 + (u3 - 2 * u2 + u) * h * m0 + (-2 * u3 + 3 * u2) * p1 + (u3 - u2) * h * m1;
}

// d/dx of hermiteValue at x = knot + u · h.
template <class T>
T hermiteDerivative(const T& p0, const T& m0, const T& p1, const T& m1, double h, double u) {
  const double u2 = u * u;
  return ((6 * u2 - 6 * u) * p0 + (6 * u - 6 * u2) * p1) / h + (3 * u2 - 4 * u + 1) * m0 + (3 * u2 - 2 * u) * m1;
}

// The segment [knots[i], knots[i + 1]] holding x (the first for x below, the last for x above);
// contract: at least two knots, increasing.
inline std::size_t hermiteSegment(const std::vector<double>& knots, double x) {
  const auto it = std::upper_bound(knots.begin(), knots.end(), x);
  const auto i = static_cast<std::size_t>(std::max<std::ptrdiff_t>(0, it - knots.begin() - 1));
  return std::min(i, knots.size() - 2);
}

}  // namespace vegstream::flight
