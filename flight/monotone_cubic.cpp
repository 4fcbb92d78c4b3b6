#include "flight/monotone_cubic.h"
#include "flight/cubic_hermite.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace vegstream::flight {
namespace {

double sign(double v) { return v > 0.0 ? 1.0 : (v < 0.0 ? -1.0 : 0.0); }

// SciPy's PchipInterpolator end slope: a three-point estimate, kept shape-preserving.
double endSlope(double h0, double h1, double m0, double m1) {
  double d = ((2.0 * h0 + h1) * m0 - h0 * m1) / (h0 + h1);
  if (sign(d) != sign(m0)) return 0.0;
  if (sign(m0) != sign(m1) && std::abs(d) > 3.0 * std::abs(m0)) return 3.0 * m0;
  return d;
}

}  // namespace

MonotoneCubic::MonotoneCubic(std::vector<double> x, std::vector<double> y)
    : x_(std::move(x)), y_(std::move(y)), d_(x_.size(), 0.0) {
  assert(!x_.empty() && x_.size() == y_.size());
  const std::size_t n = x_.size();
  if (n < 2) return;
  std::vector<double> h(n - 1), m(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    h[i] = x_[i + 1] - x_[i];
    assert(h[i] > 0.0 && "x must be strictly increasing");
    m[i] = (y_[i + 1] - y_[i]) / h[i];
  }
  if (n == 2) {
    d_[0] = d_[1] = m[0];
    return;
  }
  for (std::size_t k = 1; k + 1 < n; ++k) {
    if (m[k - 1] * m[k] <= 0.0) continue;  // a local extremum or a flat side: slope 0
    const double w1 = 2.0 * h[k] + h[k - 1];
    const double w2 = h[k] + 2.0 * h[k - 1];
    d_[k] = (w1 + w2) / (w1 / m[k - 1] + w2 / m[k]);
  }
  d_[0] = endSlope(h[0], h[1], m[0], m[1]);
  d_[n - 1] = endSlope(h[n - 2], h[n - 3], m[n - 2], m[n - 3]);
}

std::size_t MonotoneCubic::segment(double x) const { return hermiteSegment(x_, x); }

double MonotoneCubic::value(double x) const {
  if (x_.size() == 1 || x <= x_.front()) return y_.front();
  if (x >= x_.back()) return y_.back();
  const std::size_t i = segment(x);
  const double h = x_[i + 1] - x_[i];
  return hermiteValue(y_[i], d_[i], y_[i + 1], d_[i + 1], h, (x - x_[i]) / h);
}

double MonotoneCubic::derivative(double x) const {
  if (x_.size() == 1 || x < x_.front() || x > x_.back()) return 0.0;
  const std::size_t i = segment(x);
  const double h = x_[i + 1] - x_[i];
  return hermiteDerivative(y_[i], d_[i], y_[i + 1], d_[i + 1], h, (x - x_[i]) / h);
}

}  // namespace vegstream::flight
