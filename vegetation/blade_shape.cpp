// The blade-shape solver (blade_shape.h): core seed ../shared/seeds/001_3eca9f2c7752e4fb.txt
// §2.3 eq. 5–12, general torque balance derived in the header.

#include "vegetation/blade_shape.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>
#include <string>

namespace vegstream::vegetation {

namespace {

using Vec = std::vector<double>;

size_t idx(int i) { return static_cast<size_t>(i); }

// Segment j's (0-based) lever weight: a full lever for the N − 1 − j segments above it and a half
// for itself.
double leverWeight(int n, int j) { return static_cast<double>(n - j) - 0.5; }

// F (and, when jac is given, its Jacobian) at phi. Suffix sums make both O(N²) at most: F_n needs
// Σ_{j≥n} c_j sin θ′_j, J_nm needs Σ_{j≥max(n,m)} c_j cos θ′_j.
void evaluate(std::span<const double> phi, double k, double tilt, Vec& f, Vec* jac) {
  const int n = static_cast<int>(phi.size());
  Vec theta(idx(n)), sinSum(idx(n) + 1, 0.0), cosSum(idx(n) + 1, 0.0);
  double acc = 0.0;
  for (int j = 0; j < n; ++j) theta[idx(j)] = acc += phi[idx(j)];
  for (int j = n - 1; j >= 0; --j) {
    sinSum[idx(j)] = sinSum[idx(j) + 1] + leverWeight(n, j) * std::sin(theta[idx(j)]);
    cosSum[idx(j)] = cosSum[idx(j) + 1] + leverWeight(n, j) * std::cos(theta[idx(j)]);
  }
  f.assign(idx(n), 0.0);
  for (int i = 0; i < n; ++i) f[idx(i)] = sinSum[idx(i)] - k * (phi[idx(i)] - (i == 0 ? tilt : 0.0));
  if (!jac) return;
  jac->assign(idx(n * n), 0.0);
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) (*jac)[idx(r * n + c)] = cosSum[idx(std::max(r, c))] - (r == c ? k : 0.0);
}

double maxAbs(const Vec& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}
double sumSquares(const Vec& v) {
  double s = 0.0;
  for (double x : v) s += x * x;
  return s;
}

// Solves a x = b (n × n, row-major) by Gaussian elimination with partial pivoting; false when
// singular to working precision (n ≤ 16: nothing cleverer needed).
bool solveLinear(Vec a, Vec b, Vec& x) {
  const int n = static_cast<int>(b.size());
  for (int c = 0; c < n; ++c) {
    int p = c;
    for (int r = c + 1; r < n; ++r)
      if (std::abs(a[idx(r * n + c)]) > std::abs(a[idx(p * n + c)])) p = r;
    if (!(std::abs(a[idx(p * n + c)]) > 1e-300)) return false;
    if (p != c) {
      for (int k = 0; k < n; ++k) std::swap(a[idx(p * n + k)], a[idx(c * n + k)]);
      std::swap(b[idx(p)], b[idx(c)]);
    }
    for (int r = c + 1; r < n; ++r) {
      const double m = a[idx(r * n + c)] / a[idx(c * n + c)];
      for (int k = c; k < n; ++k) a[idx(r * n + k)] -= m * a[idx(c * n + k)];
      b[idx(r)] -= m * b[idx(c)];
    }
  }
  x.assign(idx(n), 0.0);
  for (int r = n - 1; r >= 0; --r) {
    double s = b[idx(r)];
    for (int k = r + 1; k < n; ++k) s -= a[idx(r * n + k)] * x[idx(k)];
    x[idx(r)] = s / a[idx(r * n + r)];
  }
  return std::all_of(x.begin(), x.end(), [](double v) { return std::isfinite(v); });
}

constexpr double kTolerance = 1e-12;   // the goal for max |F_n|
constexpr double kAcceptable = 1e-10;  // below this a step counts as converged when 1e-12 is out of reach

// Damped Newton from phi: the full step, halved until ‖F‖² decreases (Armijo with c = 1e-4).
// Returns max |F| at the end; iterations are added to `iterations`.
double newton(Vec& phi, double k, double tilt, int& iterations) {
  Vec f, jac, step, trial, ft;
  evaluate(phi, k, tilt, f, &jac);
  for (int it = 0; it < 60 && maxAbs(f) > kTolerance; ++it) {
    Vec minusF(f.size());
    for (size_t i = 0; i < f.size(); ++i) minusF[i] = -f[i];
    if (!solveLinear(jac, minusF, step)) break;
    ++iterations;
    const double merit = sumSquares(f);
    bool accepted = false;
    for (double lambda = 1.0; lambda > 1e-6; lambda *= 0.5) {
      trial = phi;
      for (size_t i = 0; i < phi.size(); ++i) trial[i] += lambda * step[i];
      evaluate(trial, k, tilt, ft, nullptr);
      if (sumSquares(ft) <= (1.0 - 1e-4 * lambda) * merit) {
        accepted = true;
        break;
      }
    }
    if (!accepted) break;  // at the rounding floor (or stuck): the caller judges the residual
    phi = trial;
    evaluate(phi, k, tilt, f, &jac);
  }
  return maxAbs(f);
}

Error invalid(std::string m) { return makeError(ErrorKind::InvalidInput, std::move(m)); }

Status checkArguments(double stiffness, int segments, double tilt) {
  if (!std::isfinite(stiffness) || stiffness <= 0.0)
    return invalid("blade shape: stiffness k′ " + std::to_string(stiffness) + " must be a finite number > 0");
  if (segments < 1 || segments > kMaxBladeSegments)
    return invalid("blade shape: segments " + std::to_string(segments) + " must be 1 … " +
                   std::to_string(kMaxBladeSegments));
  if (!std::isfinite(tilt) || tilt < 0.0 || tilt >= 0.5 * std::numbers::pi)
    return invalid("blade shape: root tilt " + std::to_string(tilt) + " rad must be in [0, π/2)");
  return {};
}

}  // namespace

double bladeTorqueResidual(std::span<const double> phi, double stiffness, int n, double rootTilt) {
  if (n < 1 || n > static_cast<int>(phi.size())) return std::nan("");
  Vec f;
  evaluate(phi, stiffness, rootTilt, f, nullptr);
  return f[idx(n - 1)];
}

std::vector<double> bladeTorqueJacobian(std::span<const double> phi, double stiffness) {
  Vec f, jac;
  evaluate(phi, stiffness, 0.0, f, &jac);  // the tilt only shifts F, never its derivative
  return jac;
}

double criticalStiffness(int segments) {
  if (segments < 1 || segments > kMaxBladeSegments) return std::nan("");
  // A = the Jacobian at φ = 0 with k′ = 0. Its largest eigenvalue by cyclic Jacobi rotations:
  // symmetric and tiny, so this is exact to rounding and needs no library.
  const Vec zero(idx(segments), 0.0);
  Vec a = bladeTorqueJacobian(zero, 0.0);
  const int n = segments;
  for (int sweep = 0; sweep < 100; ++sweep) {
    double off = 0.0;
    for (int p = 0; p < n; ++p)
      for (int q = p + 1; q < n; ++q) off += a[idx(p * n + q)] * a[idx(p * n + q)];
    if (off < 1e-30) break;
    for (int p = 0; p < n; ++p)
      for (int q = p + 1; q < n; ++q) {
        const double apq = a[idx(p * n + q)];
        if (std::abs(apq) < 1e-300) continue;
        const double tau = (a[idx(q * n + q)] - a[idx(p * n + p)]) / (2.0 * apq);
        const double t = (tau >= 0 ? 1.0 : -1.0) / (std::abs(tau) + std::sqrt(1.0 + tau * tau));
        const double c = 1.0 / std::sqrt(1.0 + t * t), s = t * c;
        for (int k = 0; k < n; ++k) {  // columns p, q
          const double akp = a[idx(k * n + p)], akq = a[idx(k * n + q)];
          a[idx(k * n + p)] = c * akp - s * akq;
          a[idx(k * n + q)] = s * akp + c * akq;
        }
        for (int k = 0; k < n; ++k) {  // rows p, q
          const double apk = a[idx(p * n + k)], aqk = a[idx(q * n + k)];
          a[idx(p * n + k)] = c * apk - s * aqk;
          a[idx(q * n + k)] = s * apk + c * aqk;
        }
      }
  }
  double largest = a[0];
  for (int i = 1; i < n; ++i) largest = std::max(largest, a[idx(i * n + i)]);
  return largest;
}

Result<BladeShape> solveBladeShape(double stiffness, const BladeShapeOptions& o) {
  if (Status s = checkArguments(stiffness, o.segments, o.rootTiltRad); !s) return s.error();
  const int n = o.segments;
  const double tilt = o.rootTiltRad;
  const double kc = criticalStiffness(n);

  // Start stiff, where the shape is nearly the rest shape: the linearised solution
  // φ = k′ (k′ I − A)⁻¹ φ₀ e₁ (k′ I − A is positive definite there) is an excellent first guess.
  double k = std::max(stiffness, 4.0 * kc);
  Vec phi(idx(n), 0.0), f, jac, rhs(idx(n), 0.0);
  {
    evaluate(Vec(idx(n), 0.0), k, 0.0, f, &jac);  // jac = A − k′ I at φ = 0
    for (double& v : jac) v = -v;
    rhs[0] = k * tilt;
    if (!solveLinear(jac, rhs, phi)) {
      phi.assign(idx(n), 0.0);
      phi[0] = tilt;
    }
  }
  int iterations = 0;
  double residual = newton(phi, k, tilt, iterations);
  if (!(residual <= kAcceptable))
    return makeError(ErrorKind::Internal, "blade shape: no convergence at the stiff start k′ = " + std::to_string(k));

  // Continuation to the target: geometric steps in k′ (the shape depends on k′ / k_c), a tangent
  // predictor dφ/dk′ = J⁻¹ (φ − φ₀ e₁) (from ∂F/∂k′ = −(φ − φ₀ e₁)), Newton as corrector; a step
  // that fails is retried shorter, so the path never jumps to another branch.
  double ratio = 0.8;
  while (k > stiffness) {
    const double kNext = std::max(stiffness, k * ratio);
    Vec tangent, dir = phi;
    dir[0] -= tilt;
    evaluate(phi, k, tilt, f, &jac);
    Vec trial = phi;
    if (solveLinear(jac, dir, tangent))
      for (size_t i = 0; i < trial.size(); ++i) trial[i] += tangent[i] * (kNext - k);
    const double r = newton(trial, kNext, tilt, iterations);
    if (r <= kAcceptable) {
      phi = trial;
      k = kNext;
      residual = r;
      ratio = std::max(0.5, ratio * 0.9);  // lengthen again after a success, within bounds
      ratio = std::min(ratio, 0.8);
    } else {
      ratio = std::sqrt(ratio);  // shorter step: ratio → 1
      if (ratio > 1.0 - 1e-6)
        return makeError(ErrorKind::Internal, "blade shape: continuation stalled at k′ = " + std::to_string(k));
    }
  }

  BladeShape shape;
  shape.stiffness = stiffness;
  shape.phi = phi;
  shape.residual = residual;
  shape.iterations = iterations;
  shape.points.assign(1, glm::dvec2(0.0));
  double theta = 0.0;
  for (int j = 0; j < n; ++j) {
    theta += phi[idx(j)];
    shape.inclination.push_back(theta);
    shape.points.push_back(shape.points.back() + glm::dvec2(std::sin(theta), std::cos(theta)));
  }
  return shape;
}

Result<BladeShapeTable> buildBladeShapeTable(int segments, int rows, double kMin, double kMax, double rootTilt) {
  if (rows < 2) return invalid("blade shape table: rows " + std::to_string(rows) + " must be ≥ 2");
  if (!std::isfinite(kMin) || kMin <= 0.0)
    return invalid("blade shape table: kMin " + std::to_string(kMin) + " must be a finite number > 0");
  if (!std::isfinite(kMax) || !(kMax > kMin))
    return invalid("blade shape table: kMax " + std::to_string(kMax) + " must be finite and > kMin");
  BladeShapeTable table{segments, rows, kMin, kMax, {}};
  table.texels.reserve(idx(rows * segments * 4));
  for (int r = 0; r < rows; ++r) {
    // Each row solved on its own (the same continuation as solveBladeShape): the table is exactly
    // what the solver gives at that k′, whatever the row count.
    const double k = r == rows - 1 ? kMax : kMin * std::pow(kMax / kMin, static_cast<double>(r) / (rows - 1));
    auto shape = solveBladeShape(k, {segments, rootTilt});
    if (!shape) return shape.error();
    for (int s = 0; s < segments; ++s) {
      const glm::dvec2 p = shape->points[idx(s) + 1];
      table.texels.push_back(static_cast<float>(p.x));
      table.texels.push_back(static_cast<float>(p.y));
      table.texels.push_back(static_cast<float>(shape->inclination[idx(s)]));
      table.texels.push_back(0.0f);
    }
  }
  return table;
}

double minimumRelativeStiffness() {
  static const double value = [] {
    const double kc = criticalStiffness(kBladeShapeSegments);
    BladeShapeOptions o;
    o.segments = kBladeShapeSegments;
    const auto tipHeight = [&](double s) {
      const Result<BladeShape> b = solveBladeShape(s * kc, o);
      assert(b && "the default blade solves at every stiffness (blade_shape_test)");
      return b ? b->points.back().y : 0.0;
    };
    double lo = 0.2, hi = 1.0;  // tip below the root at 0.2 k_c, above it at k_c
    assert(tipHeight(lo) < 0.0 && tipHeight(hi) > 0.0);
    while (hi - lo > 1e-4) {
      const double mid = 0.5 * (lo + hi);
      (tipHeight(mid) < 0.0 ? lo : hi) = mid;
    }
    return hi;
  }();
  return value;
}

}  // namespace vegstream::vegetation
