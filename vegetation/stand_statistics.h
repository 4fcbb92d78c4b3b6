#pragma once
// Spatial statistics of a stand of trees (issue 41 item 4), to measure that placement looks like
// a stand and not a lattice.
//
// Clark–Evans aggregation index (P. J. Clark and F. C. Evans, "Distance to nearest neighbor as a
// measure of spatial relationships in populations", Ecology 35(4), 1954): R = r̄_A / r̄_E, the mean
// distance from each tree to its nearest neighbour over the mean expected of a Poisson (complete
// spatial randomness) pattern of the same density. R = 1: random; R < 1: clumped; R > 1: regular
// (a square lattice gives 2, a hexagonal one 2.15). Natural stands give about 0.9–1.3.
//
// Edge correction (K. P. Donnelly, "Simulations to determine the variance and edge effect of total
// nearest neighbour distance", in Simulation Methods in Archaeology, Cambridge UP, 1978): nearest
// neighbours are searched inside the rectangle only, and the expectation is corrected for the
// rectangle's perimeter P: r̄_E = 0.5 √(A / N) + (0.0514 + 0.041 / √N) · P / N.
//
// Coefficient of variation: the sample standard deviation over the mean.

#include <span>

#include <glm/vec2.hpp>

namespace vegstream::vegetation {

struct ClarkEvans {
  double r = 0.0;             // R = meanNearestM / expectedM (0 when fewer than 2 points)
  double meanNearestM = 0.0;  // r̄_A
  double expectedM = 0.0;     // r̄_E with Donnelly's correction
  size_t n = 0;
};

// Points in metres inside the axis-aligned rectangle [x0, x1) × [y0, y1); points outside it are
// left out. Contract: x0 < x1, y0 < y1. O(N) expected (a bucket grid).
ClarkEvans clarkEvans(std::span<const glm::dvec2> points, double x0, double y0, double x1, double y1);

// Standard deviation (n − 1) over the mean; 0 for fewer than 2 values or a mean of 0.
double coefficientOfVariation(std::span<const double> values);

}  // namespace vegstream::vegetation
