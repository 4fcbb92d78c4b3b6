#pragma once
// The tapered-beam deflection of a branch, seed ../shared/seeds/002_e402409f584e6b0c.txt §4.4
// (notes 002 §1.3, eq. 4.1–4.8, Table 4.1), and its two-coefficient fit u ≈ c₂x² + c₄x⁴ that the
// vertex shader evaluates (simulation/shared/tree_bending.glsl beamU, TreeBranch::c2/c4).
//
// Model. A branch is an Euler–Bernoulli beam of unit length, clamped at the root, free at the
// tip, its radius tapering linearly from r₁ to α r₁ (α = tip / root radius, eq. 4.4), under a
// uniform transverse load F (eq. 4.1–4.3). With I(x) = π r₁⁴ ξ⁴ / 4, ξ = 1 + (α − 1)x (eq. 4.6),
// the bending moment F(1 − x)²/2 gives
//   u''(x) = (2 / π) (1 − x)² / ξ⁴        (F / (E′ r₁⁴) = 1, the normalisation of Table 4.1),
// whose solution with u(0) = u′(0) = 0 is eq. 4.7 (checked here against a direct quadrature of
// the equation above to 1e-15). The uniform beam α = 1 is (6x² − 4x³ + x⁴) / (6π).
//
// Numerics. Eq. 4.7 divides by (α − 1)⁴ and subtracts terms of size |(α − 1)x| / (α − 1)⁴ to get
// a result of size x²: near α = 1 or near the root it cancels catastrophically. For |(α − 1)x| <
// 0.3 the deflection is summed from the power series of 1 / ξ⁴ instead (≤ 60 terms to 1e-19);
// above that the closed form is evaluated in long double, where its cancellation costs at most a
// factor 40 (|(α−1)x| ≥ 0.3, x ≤ 1).
//
// The fit. x² and x⁴ are the seed's basis (eq. 4.8). Three fits:
//  - fitTaperedBeamLeastSquares: the plain least-squares fit of u itself over x ∈ [0, 1] (2001
//    samples) — the seed's Table 4.1, reproduced within 1.4e-3 (tests/vegetation/tree_bending_test).
//  - fitTaperedBeam: the shape the shader uses (TreeBranch::c2/c4), normalised to a unit tip
//    deflection (c₂ + c₄ = 1, so the branch's amplitude A is its tip deflection). With the tip
//    fixed one coefficient is left; it is chosen to minimise the largest error (minimax, on 801
//    samples) rather than the squared error, because what is visible and what the issue's
//    acceptance measures ("within 1 %") is the worst point. Worst errors of the shape, in tip
//    deflections: α = 0.1: 0.33 %, 0.15: 0.81 %, 0.2: 1.06 %, 0.3: 0.98 %, 0.5: 0.18 %,
//    0.8: 1.13 %, 1.0: 1.88 % — above 1 % for α = 0.2, 0.8 and 1.0, and no c₂ does better.
//  - fitTaperedBeamFreeTip: the minimax fit of the shape u / u(1) with both coefficients free (so
//    c₂ + c₄ = 1 only within 2 %, the tip off by as much): 0.32, 0.58, 0.81, 0.79, 0.15, 0.96,
//    1.62 % for the same α — within 1 % for every α < 1. Not what the models use (their
//    contract is c₂ + c₄ = 1); switching is one line in tree_model.cpp. The uniform beam's x³ term
//    is not in the basis: a cubic c₂x² + c₃x³ + c₄x⁴ with the tip fixed would stay below 0.6 % for
//    α ≥ 0.1 with the same two stored floats.

namespace vegstream::vegetation {

// u(x) of a tapered beam of taper α (tip / root radius, > 0) at x ∈ [0, 1], eq. 4.7 with
// E′F / r₁⁴ = 1 (Table 4.1's normalisation).
double taperedBeamDeflection(double alpha, double x);

// u(x) ≈ c₂x² + c₄x⁴.
struct BeamFit {
  float c2 = 0.0f;
  float c4 = 0.0f;
};

// The least-squares fit of u itself (not normalised), as Table 4.1.
BeamFit fitTaperedBeamLeastSquares(double alpha);

// The shape u(x) / u(1) the shader bends with: c₂ + c₄ = 1 (exactly, in float: c₄ = 1 − c₂),
// c₂ minimising the largest error over [0, 1].
BeamFit fitTaperedBeam(double alpha);

// The minimax fit of u(x) / u(1) with c₂ and c₄ both free (not normalised: c₂ + c₄ ≈ 1).
BeamFit fitTaperedBeamFreeTip(double alpha);

// max over x ∈ [0, 1] of |c₂x² + c₄x⁴ − u(x) / u(1)|: a normalised fit's worst error in tip
// deflections (801 samples).
double beamFitMaxError(double alpha, BeamFit fit);

}  // namespace vegstream::vegetation
