// vegetation/tree_bending.h and simulation/shared/tree_bending.glsl (through
// simulation/shared_code.h, the text the GPU runs): the tapered beam of seed
// ../shared/seeds/002_e402409f584e6b0c.txt §4.4 against a quadrature of its equation, the fit
// against Table 4.1 and against the analytic deflection (issue 20: "bending matches the analytic
// beam deflection for a static load within 1 %"), the length correction, the branch's wind
// amplitude and the leaf flutter.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include <gtest/gtest.h>

#include "simulation/shared_code.h"
#include "vegetation/tree_bending.h"

namespace vegstream::vegetation {
namespace {

// u(x) = ∫₀ˣ (x − z) u''(z) dz with u'' = (2/π)(1 − z)² / (1 + (α − 1)z)⁴, Simpson's rule.
double deflectionByQuadrature(double alpha, double x) {
  constexpr int kIntervals = 20000;
  const double h = x / kIntervals;
  double sum = 0.0;
  for (int i = 0; i <= kIntervals; ++i) {
    const double z = h * i;
    const double xi = 1.0 + (alpha - 1.0) * z;
    const double f = (x - z) * (2.0 / std::numbers::pi) * (1.0 - z) * (1.0 - z) / (xi * xi * xi * xi);
    sum += f * (i == 0 || i == kIntervals ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0));
  }
  return sum * h / 3.0;
}

TEST(TreeBending, DeflectionSolvesTheBeamEquation) {
  for (double alpha : {0.05, 0.1, 0.2, 0.5, 0.8, 0.99, 0.9999, 1.0}) {
    for (double x : {1e-3, 0.01, 0.1, 0.35, 0.5, 0.9, 1.0}) {
      const double expected = deflectionByQuadrature(alpha, x);
      EXPECT_NEAR(taperedBeamDeflection(alpha, x), expected, 1e-12 * expected + 1e-18) << alpha << " " << x;
    }
  }
  // The uniform beam, (6x² − 4x³ + x⁴) / (6π), and the root.
  for (double x : {0.0, 0.2, 1.0})
    EXPECT_NEAR(taperedBeamDeflection(1.0, x), (6 * x * x - 4 * x * x * x + x * x * x * x) / (6 * std::numbers::pi),
                1e-15);
  EXPECT_EQ(taperedBeamDeflection(0.2, 0.0), 0.0);
  // Series and closed form meet where the evaluation switches (|α − 1| x = 0.3; u′ ≈ 0.33 there).
  EXPECT_NEAR(taperedBeamDeflection(0.5, 0.6 - 1e-12), taperedBeamDeflection(0.5, 0.6 + 1e-12), 1e-12);
}

// Table 4.1 (normalised to E′F / r₁⁴ = 1).
TEST(TreeBending, LeastSquaresFitReproducesTable41) {
  struct Row {
    double alpha, c2, c4;
  };
  for (const Row& row : {Row{0.1, 0.3326, 0.398924}, Row{0.2, 0.374571, 0.129428}, Row{0.3, 0.364816, 0.024577}}) {
    const BeamFit fit = fitTaperedBeamLeastSquares(row.alpha);
    std::printf("alpha %.1f: c2 %.6f (table %.6f), c4 %.6f (table %.6f)\n", row.alpha, fit.c2, row.c2, fit.c4, row.c4);
    EXPECT_NEAR(fit.c2, row.c2, 2e-3) << row.alpha;
    EXPECT_NEAR(fit.c4, row.c4, 2e-3) << row.alpha;
  }
}

// The acceptance: the shape the models bend with (tree_model.cpp: the free-tip fit)
// against the analytic deflection under a static load, worst error over x in tip deflections:
// within 1 % for every taper the catalog allows (0.1 … 0.8). Outside it, refused by the catalog and
// held to their measured figures: α = 0.05 (2.28 %), 0.9 (1.30 %), 1.0 (the uniform beam, 1.62 %:
// the x², x⁴ basis lacks its x³ term). The tip-normalised fit (c₂ + c₄ = 1) misses 1 % at α = 0.2
// (1.06 %) and 0.8 (1.13 %).
TEST(TreeBending, NormalisedFitMatchesTheAnalyticBeam) {
  struct Case {
    double alpha, bound;
  };
  for (const Case& c : {Case{0.05, 0.0298}, Case{0.1, 0.01}, Case{0.15, 0.01}, Case{0.2, 0.0107}, Case{0.3, 0.01},
                        Case{0.5, 0.01}, Case{0.8, 0.0114}, Case{0.9, 0.02}, Case{1.0, 0.0189}}) {
    const BeamFit fit = fitTaperedBeam(c.alpha);
    EXPECT_NEAR(fit.c2 + fit.c4, 1.0f, 1e-6f);
    const double error = beamFitMaxError(c.alpha, fit);
    EXPECT_LT(error, c.bound) << c.alpha;
    // Optimal with the tip fixed: no c₂ on a 0.0005 grid does better.
    double best = 1e9;
    for (int i = 0; i <= 1000; ++i) {
      const float c2 = fit.c2 - 0.25f + 0.0005f * static_cast<float>(i);
      best = std::min(best, beamFitMaxError(c.alpha, {c2, 1.0f - c2}));
    }
    EXPECT_GT(best, 0.9999 * error) << c.alpha;
    // The free-tip fit: within 1 % below α = 1, the tip within 2 %, and optimal near it.
    const BeamFit free = fitTaperedBeamFreeTip(c.alpha);
    const double freeError = beamFitMaxError(c.alpha, free);
    const bool allowed = c.alpha >= 0.1 && c.alpha <= 0.8;  // the catalog's taper range
    EXPECT_LT(freeError, allowed ? 0.01 : (c.alpha < 0.1 ? 0.0229 : c.alpha < 1.0 ? 0.0131 : 0.0163)) << c.alpha;
    EXPECT_NEAR(free.c2 + free.c4, 1.0f, allowed ? 0.02f : 0.03f) << c.alpha;
    double bestFree = 1e9;
    for (int i = -20; i <= 20; ++i)
      for (int j = -20; j <= 20; ++j)
        bestFree = std::min(bestFree, beamFitMaxError(c.alpha, {free.c2 + 0.001f * static_cast<float>(i),
                                                                free.c4 + 0.0005f * static_cast<float>(j)}));
    EXPECT_GT(bestFree, 0.9999 * freeError) << c.alpha;
    std::printf("alpha %.2f: c2 %.5f c4 %.5f, worst error %.3f %% of the tip; free tip: c2 %.5f c4 %.5f, %.3f %%\n",
                c.alpha, fit.c2, fit.c4, 100 * error, free.c2, free.c4, 100 * freeError);
  }
}

}  // namespace
}  // namespace vegstream::vegetation

namespace vegstream::simulation {
namespace {
using namespace shader;

// The centre line of a bent branch (unit length): its length and its tip's distance from the
// root, with the length correction (branchOffset) or without (the transverse deflection alone).
struct CentreLine {
  float length, chord;
};
enum class Correction { None, Seed, Shared };
CentreLine bentCentreLine(vegetation::BeamFit fit, float amplitude, Correction correction) {
  const vec3 t(0.0f, 0.0f, 1.0f), r(1.0f, 0.0f, 0.0f), s(0.0f, 1.0f, 0.0f);
  vec3 previous(0.0f);
  float length = 0.0f;
  for (int i = 1; i <= 2000; ++i) {
    const float x = static_cast<float>(i) / 2000.0f;
    const float u = amplitude * beamU(fit.c2, fit.c4, x), du = amplitude * beamDU(fit.c2, fit.c4, x);
    const float stretch = std::sqrt(1.0f + du * du), d = u * du / (stretch + 1.0f);  // eq. 4.9: (u/u′)(s − 1)
    vec3 p = t * x + r * u;
    if (correction == Correction::Seed) p = t * (x - d / stretch) + r * (u / stretch);  // eq. 4.10
    if (correction == Correction::Shared)
      p = t * x + branchOffset(t, r, s, 1.0f, fit.c2, fit.c4, x, vec2(amplitude, 0.0f));
    length += glm::length(p - previous);
    previous = p;
  }
  return {length, glm::length(previous)};
}

TEST(TreeBendingShader, SmallAmplitudeIsTheBeam) {
  const vegetation::BeamFit fit = vegetation::fitTaperedBeam(0.2);
  const vec3 t = normalize(vec3(0.3f, 0.2f, 1.0f));
  const vec3 r = normalize(cross(vec3(0.0f, 0.0f, 1.0f), t));
  const vec3 s = cross(t, r);
  const float L = 3.5f, A = 1e-3f;
  for (float x : {0.1f, 0.4f, 0.75f, 1.0f}) {
    const vec3 o = branchOffset(t, r, s, L, fit.c2, fit.c4, x, vec2(A, 0.0f));
    const float expected = A * L * beamU(fit.c2, fit.c4, x);
    EXPECT_NEAR(dot(o, r), expected, 1e-4f * expected) << x;
    EXPECT_NEAR(dot(o, s), 0.0f, 1e-9f) << x;
    EXPECT_LT(std::abs(dot(o, t)), 2.0f * A * expected) << x;  // the correction is second order in A
  }
  EXPECT_FLOAT_EQ(beamU(fit.c2, fit.c4, 1.0f), 1.0f);
  // du/dx against a central difference.
  const float h = 1e-3f;
  EXPECT_NEAR(beamDU(fit.c2, fit.c4, 0.6f),
              (beamU(fit.c2, fit.c4, 0.6f + h) - beamU(fit.c2, fit.c4, 0.6f - h)) / (2 * h), 1e-3f);
  EXPECT_EQ(branchOffset(t, r, s, L, fit.c2, fit.c4, 0.7f, vec2(0.0f)), vec3(0.0f));
}

// A strong bend, A = 0.5 (the tip half a branch length aside): the corrected centre line keeps
// its length; the transverse deflection alone stretches it by 14–16 % (its tip 11.8 % further
// out), and the seed's own d (eq. 4.9) shortens it by 3–9 % for α < 1 (it is exact only for a straight,
// rotated branch). The tip's chord is shorter than L by construction (a bent branch of length L).
TEST(TreeBendingShader, LengthCorrectionKeepsTheCentreLine) {
  for (double alpha : {0.1, 0.2, 0.5, 1.0}) {
    const vegetation::BeamFit fit = vegetation::fitTaperedBeam(alpha);
    for (float amplitude : {0.25f, 0.5f}) {
      const CentreLine bent = bentCentreLine(fit, amplitude, Correction::Shared);
      const CentreLine stretched = bentCentreLine(fit, amplitude, Correction::None);
      const CentreLine seed = bentCentreLine(fit, amplitude, Correction::Seed);
      std::printf("alpha %.1f A %.2f: length %.4f (uncorrected %.4f, eq. 4.9 %.4f), chord %.4f (uncorrected %.4f)\n",
                  alpha, amplitude, bent.length, stretched.length, seed.length, bent.chord, stretched.chord);
      if (alpha < 1.0) {
        EXPECT_LT(std::abs(bent.length - 1.0f), std::abs(seed.length - 1.0f)) << alpha;
      }
      const float bound = amplitude < 0.3f ? 0.01f : (alpha < 0.15 ? 0.04f : 0.03f);
      EXPECT_NEAR(bent.length, 1.0f, bound) << alpha << " " << amplitude;
      EXPECT_GT(stretched.length - 1.0f, 2.0f * std::abs(bent.length - 1.0f)) << alpha << " " << amplitude;
    }
  }
}

TEST(TreeBendingShader, NoWindNoAmplitude) {
  const vec3 r(1.0f, 0.0f, 0.0f), s(0.0f, 0.0f, 1.0f);
  for (float time : {0.0f, 1.3f, 1000.0f}) {
    EXPECT_EQ(branchAmplitude(vec3(0.0f), r, s, 0.1f, 1.2f, 0.4f, time), vec2(0.0f));
    const vec2 faint = branchAmplitude(vec3(1e-4f, 0.0f, 0.0f), r, s, 0.1f, 1.2f, 0.4f, time);
    EXPECT_TRUE(std::isfinite(faint.x) && std::isfinite(faint.y));
    const vec2 light = branchAmplitude(vec3(0.02f, 0.0f, 0.0f), r, s, 0.1f, 1.2f, 0.4f, time);
    EXPECT_TRUE(std::isfinite(light.x) && std::isfinite(light.y));
    EXPECT_LT(length(light), 1e-4f);
  }
}

// The time average is the static load compliance (W·r)|W| / 100; the oscillation's RMS is 0.35 of
// the static part at 10 m/s for a 1 Hz branch.
TEST(TreeBendingShader, SteadyWindAveragesToTheStaticLoad) {
  const vec3 r = normalize(vec3(1.0f, 1.0f, 0.0f));
  const vec3 s = vec3(0.0f, 0.0f, 1.0f);
  const vec3 wind(10.0f, 3.0f, 0.0f);
  const float compliance = 0.08f;
  const float expected = compliance * dot(wind, r) * length(wind) / 100.0f;
  for (float frequency : {0.5f, 1.0f, 2.7f}) {
    double sumR = 0.0, sumS = 0.0, sumSquares = 0.0;
    constexpr int kSamples = 2000;
    for (int i = 0; i < kSamples; ++i) {
      const vec2 a = branchAmplitude(wind, r, s, compliance, frequency, 1.234f, 0.437f * static_cast<float>(i));
      sumR += a.x;
      sumS += a.y;
      sumSquares += (a.x - expected) * (a.x - expected);
    }
    const double rmsShare = std::sqrt(sumSquares / kSamples) / (compliance * length(wind) * length(wind) / 100.0f);
    std::printf("f_h %.1f Hz: mean A_r %.5f (static %.5f), mean A_s %.5f, oscillation RMS %.3f of the static part\n",
                frequency, sumR / kSamples, expected, sumS / kSamples, rmsShare);
    EXPECT_NEAR(sumR / kSamples, expected, 0.02 * expected) << frequency;
    EXPECT_NEAR(sumS / kSamples, 0.0, 0.02 * expected) << frequency;
    EXPECT_GT(rmsShare, 0.1) << frequency;
    EXPECT_LT(rmsShare, 0.6) << frequency;
  }
  // 10 m/s along r, f_h = 1 Hz: the calibration point of kBranchGustGain.
  double sumSquares = 0.0;
  for (int i = 0; i < 2000; ++i) {
    const vec2 a = branchAmplitude(r * 10.0f, r, s, compliance, 1.0f, 0.3f, 0.437f * static_cast<float>(i));
    sumSquares += (a.x - compliance) * (a.x - compliance);
  }
  EXPECT_NEAR(std::sqrt(sumSquares / 2000.0) / compliance, 0.35, 0.03);
}

TEST(TreeBendingShader, LeafFlutterIsSmall) {
  const vec3 n(0.0f, 0.0f, 1.0f), tangent(1.0f, 0.0f, 0.0f);
  float peak = 0.0f;
  for (int i = 0; i < 4000; ++i) {
    const vec3 o = leafFlutter(n, tangent, 1.0f, 4.0f, 0.7f, 10.0f, 0.01f * static_cast<float>(i));
    peak = std::max(peak, length(o));
  }
  std::printf("leaf flutter peak at 10 m/s: %.4f m\n", peak);
  EXPECT_GT(peak, 0.02f);
  EXPECT_LT(peak, 0.04f);
  EXPECT_EQ(leafFlutter(n, tangent, 0.0f, 4.0f, 0.7f, 10.0f, 3.0f), vec3(0.0f));
  EXPECT_EQ(leafFlutter(n, tangent, 1.0f, 4.0f, 0.7f, 0.0f, 3.0f), vec3(0.0f));
}

}  // namespace
}  // namespace vegstream::simulation
