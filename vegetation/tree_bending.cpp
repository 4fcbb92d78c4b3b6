// The tapered-beam deflection and its fit, seed ../shared/seeds/002_e402409f584e6b0c.txt §4.4
// (eq. 4.7–4.8, Table 4.1); see the header for the model and the numerics.
#include "vegetation/tree_bending.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>
#include <vector>

namespace vegstream::vegetation {
namespace {

// Below this |(α − 1)x| the series; above it eq. 4.7 in long double.
constexpr double kSeriesLimit = 0.3;

// u(x) = (2/π) Σₙ C(n+3, 3) (−b)ⁿ ∫₀ˣ∫₀ʸ (1 − z)² zⁿ dz dy, b = α − 1, from
// 1 / (1 + bz)⁴ = Σₙ C(n+3, 3) (−bz)ⁿ; each double integral is
// x^(n+2) / ((n+1)(n+2)) − 2x^(n+3) / ((n+2)(n+3)) + x^(n+4) / ((n+3)(n+4)).
long double deflectionSeries(long double b, long double x) {
  long double sum = 0.0L;
  long double power = 1.0L;  // (−bx)ⁿ
  for (int n = 0; n < 200; ++n) {
    const auto m = static_cast<long double>(n);
    const long double binomial = (m + 1.0L) * (m + 2.0L) * (m + 3.0L) / 6.0L;
    const long double integral =
        x * x *
        (1.0L / ((m + 1.0L) * (m + 2.0L)) - 2.0L * x / ((m + 2.0L) * (m + 3.0L)) + x * x / ((m + 3.0L) * (m + 4.0L)));
    const long double term = binomial * power * integral;
    sum += term;
    if (n > 0 && std::abs(term) <= 1e-20L * std::abs(sum)) break;
    power *= -b * x;
  }
  return sum * 2.0L / std::numbers::pi_v<long double>;
}

// Eq. 4.7 as printed (with F E′ / r₁⁴ = 1), a = α, b = α − 1, ξ = 1 + bx.
long double deflectionClosedForm(long double a, long double x) {
  const long double b = a - 1.0L;
  const long double bx = b * x;
  const long double xi = 1.0L + bx;
  const long double polynomial =
      bx * (6.0L + bx * (2.0L * bx * (3.0L + (a - 3.0L) * a) + 3.0L * (4.0L + (a - 2.0L) * a)));
  const long double numerator = polynomial - 6.0L * xi * xi * std::log1p(bx);
  return numerator / (3.0L * std::numbers::pi_v<long double> * xi * xi * b * b * b * b);
}

// The normalised shape u(x) / u(1) at `samples` evenly spaced x ∈ [0, 1].
std::vector<double> normalisedShape(double alpha, int samples) {
  std::vector<double> shape(static_cast<size_t>(samples));
  const double tip = taperedBeamDeflection(alpha, 1.0);
  for (int i = 0; i < samples; ++i) {
    const double x = static_cast<double>(i) / static_cast<double>(samples - 1);
    shape[static_cast<size_t>(i)] = taperedBeamDeflection(alpha, x) / tip;
  }
  return shape;
}

// max |c₂x² + c₄x⁴ − shape(x)|, jointly convex in (c₂, c₄) (a maximum of absolute values of
// affine functions), so its minimum over c₄ for a given c₂ is convex in c₂ too.
double worstError(const std::vector<double>& shape, double c2, double c4) {
  const int samples = static_cast<int>(shape.size());
  double worst = 0.0;
  for (int i = 0; i < samples; ++i) {
    const double x = static_cast<double>(i) / static_cast<double>(samples - 1);
    const double x2 = x * x;
    worst = std::max(worst, std::abs(c2 * x2 + c4 * x2 * x2 - shape[static_cast<size_t>(i)]));
  }
  return worst;
}

// Golden-section search for the minimum of a convex f over [lo, hi]; returns the argument.
template <typename F>
double goldenMinimum(F f, double lo, double hi, double tolerance) {
  constexpr double kInvPhi = 0.6180339887498949;
  double m1 = hi - kInvPhi * (hi - lo), m2 = lo + kInvPhi * (hi - lo);
  double e1 = f(m1), e2 = f(m2);
  while (hi - lo > tolerance) {
    if (e1 < e2) {
      hi = m2, m2 = m1, e2 = e1;
      m1 = hi - kInvPhi * (hi - lo), e1 = f(m1);
    } else {
      lo = m1, m1 = m2, e1 = e2;
      m2 = lo + kInvPhi * (hi - lo), e2 = f(m2);
    }
  }
  return 0.5 * (lo + hi);
}

}  // namespace

double taperedBeamDeflection(double alpha, double x) {
  assert(alpha > 0.0 && x >= 0.0 && x <= 1.0);
  const auto b = static_cast<long double>(alpha) - 1.0L;
  const auto xl = static_cast<long double>(x);
  if (std::abs(b * xl) < kSeriesLimit) return static_cast<double>(deflectionSeries(b, xl));
  return static_cast<double>(deflectionClosedForm(static_cast<long double>(alpha), xl));
}

BeamFit fitTaperedBeamLeastSquares(double alpha) {
  // Normal equations of min Σ (c₂x² + c₄x⁴ − u)² over 2001 evenly spaced samples.
  constexpr int kSamples = 2001;
  double s44 = 0.0, s46 = 0.0, s88 = 0.0, b2 = 0.0, b4 = 0.0;
  for (int i = 0; i < kSamples; ++i) {
    const double x = static_cast<double>(i) / (kSamples - 1);
    const double x2 = x * x, x4 = x2 * x2;
    const double u = taperedBeamDeflection(alpha, x);
    s44 += x4;
    s46 += x4 * x2;
    s88 += x4 * x4;
    b2 += x2 * u;
    b4 += x4 * u;
  }
  const double det = s44 * s88 - s46 * s46;
  return {static_cast<float>((b2 * s88 - b4 * s46) / det), static_cast<float>((s44 * b4 - s46 * b2) / det)};
}

// The shapes of α ∈ [0.05, 1] need c₂ ∈ [0.1, 1.5]; the brackets leave room on both sides.
BeamFit fitTaperedBeam(double alpha) {
  const std::vector<double> shape = normalisedShape(alpha, 801);
  const auto c2 =
      static_cast<float>(goldenMinimum([&](double c) { return worstError(shape, c, 1.0 - c); }, -1.0, 3.0, 1e-9));
  return {c2, 1.0f - c2};
}

BeamFit fitTaperedBeamFreeTip(double alpha) {
  const std::vector<double> shape = normalisedShape(alpha, 801);
  // For each c₂ the best c₄ near 1 − c₂ (the tip within ±10 %).
  auto bestC4 = [&](double c2) {
    return goldenMinimum([&](double c4) { return worstError(shape, c2, c4); }, 0.9 - c2, 1.1 - c2, 1e-8);
  };
  const double c2 = goldenMinimum([&](double c) { return worstError(shape, c, bestC4(c)); }, -1.0, 3.0, 1e-8);
  return {static_cast<float>(c2), static_cast<float>(bestC4(c2))};
}

double beamFitMaxError(double alpha, BeamFit fit) {
  const std::vector<double> shape = normalisedShape(alpha, 801);
  double worst = 0.0;
  for (size_t i = 0; i < shape.size(); ++i) {
    const double x = static_cast<double>(i) / static_cast<double>(shape.size() - 1);
    const double x2 = x * x;
    worst = std::max(worst, std::abs(fit.c2 * x2 + fit.c4 * x2 * x2 - shape[i]));
  }
  return worst;
}

}  // namespace vegstream::vegetation
