#pragma once
// The static shape of a blade under its own weight, core seed
// ../shared/seeds/001_3eca9f2c7752e4fb.txt §2.3 eq. 5–12 and figs. 2–3 (issue 8).
//
// Model. N rigid segments of unit length and unit weight, joined by spring hinges of normalised
// stiffness k′ = k / (ρ h² g) (eq. 11). Hinge n (1-based, as in the paper) sits at the bottom of
// segment n; hinge 1 is the root. φ_n is hinge n's angle and θ′_n = Σ_{i≤n} φ_i segment n's
// angle from vertical (the paper's θ_n, from horizontal, is π/2 − θ′_n). Positive angles lean to
// +lateral.
//
// Torque balance at hinge n (derived here, not copied from eq. 12). Gravity pulls on every
// segment i ≥ n; its lever arm about hinge n is the horizontal distance from the hinge to the
// segment's centre, Σ_{j=n}^{i−1} sin θ′_j + ½ sin θ′_i (eq. 7's l_2, l_3 for n = 2). The spring
// resists with k′ φ_n (eq. 8). So
//
//   F_n(φ) = Σ_{i=n}^{N} [ Σ_{j=n}^{i−1} sin θ′_j + ½ sin θ′_i ] − k′ (φ_n − φ₀ δ_{n1}) = 0
//          = Σ_{j=n}^{N} (N − j + ½) sin θ′_j − k′ (φ_n − φ₀ δ_{n1}),
//
// (segment j's sine is a full lever for each of the N − j segments above it and a half lever for
// itself). For N = 3, n = 2, φ₀ = 0 this is eq. 11 exactly: (3/2) sin(φ1+φ2) + (1/2)
// sin(φ1+φ2+φ3) − k′ φ2. The printed eq. 12 has typos: its spring term says φ_k for φ_n, and its
// inner sum runs from j = 1 and then subtracts Σ_{i<n} sin θ′_i once, where the levers below hinge
// n appear N − n + 1 times — the inner sum must start at j = n (for N = 3, n = 2 the printed form
// is off by sin θ′_1 and does not give eq. 11).
//
// Root tilt. Real grass leaves the ground at an angle: the root hinge's spring is at rest at
// φ₀ = rootTilt, not at 0 (the δ_{n1} term). phi[0] is the root hinge's full angle, tilt included,
// so θ′_n = Σ phi always and points follow from phi alone; the spring deflection there is
// phi[0] − φ₀.
//
// Branch. φ = 0 with φ₀ = 0 (a straight vertical blade) is always an equilibrium; linearised,
// F ≈ (A − k′ I) φ with A_{nm} = Σ_{j ≥ max(n,m)} (N − j + ½), symmetric. F = −∇V for the energy
// V = ½ k′ Σ (φ_n − φ₀δ)² + Σ (heights of the centres), so the straight blade is stable exactly
// while k′ I − A is positive definite, i.e. k′ > λ_max(A) = criticalStiffness(N): the buckling
// stiffness, the first k′ met from stiff to soft (the largest eigenvalue) at which the linearised
// system is singular; below it a drooping shape exists. With φ₀ > 0 the imperfection removes the
// bifurcation: one stable solution connects continuously to the rest shape at k′ → ∞ and droops
// smoothly as k′ falls. solveBladeShape follows that branch by continuation in k′ from stiff
// (4 k_c or the target if stiffer) to soft, each step a tangent predictor and a damped Newton
// corrector (analytic Jacobian, backtracking on ‖F‖²). With φ₀ = 0 it returns the straight blade
// (exact, but unstable below k_c). The tip may droop below the root height at small k′: the
// ground is not modelled (neither is it in eq. 12).
//
// Scale. k′ is per hinge and normalised by the segment length h, so the same blade cut into more
// segments has a larger k′ (k′ ∝ N³ for a given continuous blade: k_c(N)/N³ tends to the
// elastica's self-weight buckling 1/7.837). For N = 4, k_c = 11.9: k′ ≈ 1–1.5 k_c gives a
// grass-like arch (tip at (2.98, 2.57) at k_c, (1.19, 3.82) at 1.5 k_c), while k′ < 0.5 k_c hangs
// below the root (k′ = 0.4: tip (0.33, −3.96)).
//
// Units (issue 18). Species catalogs, Plant::stiffness and the GPU give stiffness relative to
// the buckling stiffness, s = k′ / k_c(N), which describes the same blade whatever N: the
// renderer solves shapes at kBladeShapeSegments and multiplies by k_c there. For N = 16 the tip
// is at (lateral, height) = (0.70, 0.66) of the length at s = 1, (0.87, 0.31) at 0.8, (0.29,
// 0.96) at 1.5; below s ≈ 0.64 (minimumRelativeStiffness) it ends below the root, and catalogs
// refuse such blades.

#include <span>
#include <vector>

#include <glm/vec2.hpp>

#include "core/result.h"

namespace vegstream::vegetation {

inline constexpr int kMaxBladeSegments = 16;
// The segments the renderer solves blade shapes with (its table; blades draw ≤ 16 segments).
inline constexpr int kBladeShapeSegments = 16;
inline constexpr double kDefaultRootTiltRad = 0.1;
// The default table: log-spaced k′ over [0.05, 50], 64 rows: from a blade hanging down (k′ ≪ k_c)
// to effectively rigid for 4 segments (k′ = 50 ≈ 4 k_c: tip inclination 0.14 rad against the
// rest 0.1), so a stiffer species (gravel: 50–100) clamped to the last row is still right.
inline constexpr double kDefaultShapeTableKMin = 0.05;
inline constexpr double kDefaultShapeTableKMax = 50.0;
inline constexpr int kDefaultShapeTableRows = 64;

struct BladeShape {
  double stiffness = 0.0;           // k′
  std::vector<double> phi;          // N hinge angles, rad, root first; phi[0] includes the root tilt
  std::vector<glm::dvec2> points;   // N + 1 points (lateral, height), root first at (0, 0), unit segments
  std::vector<double> inclination;  // N segment angles from vertical θ′_n = Σ_{i≤n} phi, rad
  double residual = 0.0;            // max |F_n| at the solution
  int iterations = 0;               // Newton iterations over the whole continuation
};

struct BladeShapeOptions {
  int segments = 4;                          // N, 1 … kMaxBladeSegments
  double rootTiltRad = kDefaultRootTiltRad;  // φ₀, in [0, π/2)
};

// The drooping branch at k′ = stiffness (see above). Errors (InvalidInput): stiffness not finite or
// ≤ 0, segments outside 1 … 16, root tilt outside [0, π/2); Internal: no convergence to 1e-10.
Result<BladeShape> solveBladeShape(double stiffness, const BladeShapeOptions& o);

// F_n above for hinge n = 1 … N (1-based, the paper's numbering); NaN when n is out of range.
double bladeTorqueResidual(std::span<const double> phi, double stiffness, int n, double rootTilt);

// ∂F_n/∂φ_m, row-major N × N: Σ_{j ≥ max(n,m)} (N − j + ½) cos θ′_j − k′ δ_nm (symmetric).
std::vector<double> bladeTorqueJacobian(std::span<const double> phi, double stiffness);

// λ_max(A): the buckling k′ of the straight blade (root tilt 0). NaN for segments outside 1 … 16.
double criticalStiffness(int segments);

// The relative stiffness s = k′ / k_c at which a blade of kBladeShapeSegments segments with the
// default root tilt has its tip exactly at its root's height (≈ 0.64): softer blades end below
// the root. Found once by bisection on solveBladeShape (to 1e-4), then remembered.
double minimumRelativeStiffness();

// The shape table the GPU samples (issue 8: stored as a texture, seed §2.3 after fig. 3): row r
// (0 … rows − 1) is k′_r = kMin (kMax / kMin)^(r / (rows − 1)) — log spacing, because the shape
// changes with the ratio k′ / k_c, so every decade gets the same resolution; a shader maps k′ to
// v = log(k′ / kMin) / log(kMax / kMin). Texel (r, s), s = 0 … N − 1, at texels[(r N + s) 4 …] is
// (lateral, height) of segment s's end point (points[s + 1]), its inclination θ′_s and 0.
struct BladeShapeTable {
  int segments = 0, rows = 0;
  double kMin = 0.0, kMax = 0.0;
  std::vector<float> texels;  // rows × segments × 4
};

// Errors: as solveBladeShape, and rows < 2, kMin not finite or ≤ 0, kMax ≤ kMin or not finite.
Result<BladeShapeTable> buildBladeShapeTable(int segments, int rows, double kMin, double kMax, double rootTilt);

}  // namespace vegstream::vegetation
