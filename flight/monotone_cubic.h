#pragma once
// Monotone piecewise cubic Hermite interpolation (PCHIP): Fritsch & Carlson, "Monotone
// Piecewise Cubic Interpolation", SIAM J. Numer. Anal. 17(2), 1980, with the weighted
// harmonic-mean slopes of Fritsch & Butland (1984) and SciPy's shape-preserving end slopes.
// C¹, and between two samples the curve never leaves their range: no overshoot. Flights use it
// for altitude (a dive to 15 m must not dip to −5 m), heading, pitch and for the time → curve
// parameter map of the Catmull-Rom spline (monotone, so the camera never runs backwards).

#include <cstddef>
#include <vector>

namespace vegstream::flight {

class MonotoneCubic {
 public:
  // x strictly increasing, x.size() == y.size() >= 1 (asserted).
  MonotoneCubic(std::vector<double> x, std::vector<double> y);

  // Outside [x.front(), x.back()] the curve is constant (value of the nearest end, slope 0).
  double value(double x) const;
  double derivative(double x) const;

  std::size_t size() const { return x_.size(); }

 private:
  std::size_t segment(double x) const;  // i with x_[i] <= x < x_[i+1], clamped

  std::vector<double> x_;
  std::vector<double> y_;
  std::vector<double> d_;  // dy/dx at each sample
};

}  // namespace vegstream::flight
