// The shared simulation's model (simulation/shared/*.glsl compiled as C++ by
// simulation/shared_code.h: the same text the GPU runs): stability of the virtual blades over
// 10⁵ frames, the interaction field's recovery against its analytic decay, blade tips kept out
// of a static collider, the rest shape kept exactly without wind, and the clock of
// simulation::Simulation.

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "simulation/shared_code.h"
#include "simulation/simulation.h"
#include "vegetation/blade_shape.h"

namespace vegstream::simulation {
namespace {
using namespace shader;

// 10⁵ frames of dt drawn up to 1/20 s, each its fixed sub-steps, under a gusty wind that swings
// between calm and 40 m/s and turns: no NaN, and the energy stays below a bound (twice what the
// springs hold with every hinge at the lean limit).
TEST(VirtualBlade, HundredThousandFramesStayFiniteAndBounded) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  VirtualBlade b = virtualBladeAtRest(vec3(0.0f));
  const float bound = 2.0f * 4.0f * 0.5f * hingeStiffness(kRefStiffness) * kMaxLean * kMaxLean;
  float maxEnergy = 0.0f;
  double t = 0.0;
  long substeps = 0;
  for (int frame = 0; frame < 100000; ++frame) {
    const float dt = (1.0f / 240.0f) + u01(rng) * (1.0f / 20.0f - 1.0f / 240.0f);
    const auto steps = static_cast<int>(std::floor((t + dt) / kSubstepS) - std::floor(t / kSubstepS));
    t += dt;
    const float speed = 40.0f * u01(rng) * u01(rng);
    const float angle = 6.2831853f * static_cast<float>(frame % 500) / 500.0f;
    const vec3 wind(speed * std::cos(angle), speed * std::sin(angle), (u01(rng) - 0.5f) * 4.0f);
    for (int s = 0; s < steps; ++s) virtualBladeStep(b, wind, kSubstepS);
    substeps += steps;
    for (int i = 0; i < kBladeHinges; ++i) {
      ASSERT_TRUE(std::isfinite(b.lean[i].x) && std::isfinite(b.lean[i].y)) << "frame " << frame;
      ASSERT_TRUE(std::isfinite(b.rate[i].x) && std::isfinite(b.rate[i].y)) << "frame " << frame;
    }
    maxEnergy = std::max(maxEnergy, virtualBladeEnergy(b));
  }
  EXPECT_GT(substeps, 600000);  // dt up to 1/20 s: about 6.5 sub-steps a frame
  EXPECT_LT(maxEnergy, bound);
  EXPECT_GT(maxEnergy, 0.0f);
}

// A steady wind: the inertial blade settles where the static solve puts it, and its moments equal
// the steady wind's (the virtually-inertial model carries no lag once the wind is steady).
TEST(VirtualBlade, SettlesOnTheStaticEquilibriumUnderASteadyWind) {
  for (float speed : {2.0f, 8.0f, 15.0f}) {
    const vec3 wind(speed, 0.0f, 0.0f);
    VirtualBlade b = virtualBladeAtRest(vec3(0.0f));
    for (int s = 0; s < 240 * 20; ++s) virtualBladeStep(b, wind, kSubstepS);
    const VirtualBlade rest = virtualBladeAtRest(wind);
    for (int i = 0; i < kBladeHinges; ++i) EXPECT_NEAR(b.lean[i].x, rest.lean[i].x, 2e-3f) << speed << " m/s hinge " << i;
    EXPECT_GT(b.lean[0].x, 0.0f);  // downwind
  }
}

// Ell eq. 47: cs falls linearly at the recovery rate, so a texel hit at cs0 holds cs0 − c_r t; the
// blade's flattening follows 1 − (1 − min(cs / s, 1))³. Stepped frame by frame (60 fps, 30 s)
// against the closed form, within 2 %.
TEST(Interaction, RecoveryFollowsTheAnalyticDecay) {
  SimulationParams sim{};
  const float cs0 = 4.0f;
  vec4 texel(1.0f, 0.0f, cs0, 0.0f);
  const float dt = 1.0f / 60.0f;
  sim.field = vec4(0.0f, 0.0f, kRecoveryPerS * dt, kRecoveryPerS);
  const float s = 1.3f;
  int checked = 0;
  for (int frame = 1; frame <= 1800; ++frame) {
    texel = interactionStep(sim, texel, vec2(0.0f), 0.0f);
    const float t = static_cast<float>(frame) * dt;
    const float cs = std::max(cs0 - kRecoveryPerS * t, 0.0f);
    ASSERT_NEAR(texel.z, cs, 0.02f * std::max(cs, 0.05f)) << "t = " << t;
    const float u = std::min(cs / s, 1.0f);
    const float flatten = kMaxFlattenRad * (1.0f - (1.0f - u) * (1.0f - u) * (1.0f - u));
    const float got = length(flattenLean(texel, s));
    if (flatten > 0.05f) {
      EXPECT_NEAR(got, flatten, 0.02f * flatten) << "t = " << t;
      ++checked;
    }
  }
  EXPECT_GT(checked, 1000);
  // Harder hits take longer: cs 4 holds the blade fully down (u = 1) for (4 − 1.3) / c_r s.
  EXPECT_NEAR((cs0 - s) / kRecoveryPerS, 27.0f, 1e-3f);
}

BladeRest restOf(const vegetation::BladeShape& shape, float orientation) {
  // Points at x of the solved shape (unit length), world-oriented: the GPU samples the same shape
  // from its table (shaders/common/plant_common.glsl restAlong).
  const auto n = static_cast<int>(shape.points.size()) - 1;
  auto at = [&](float x) {
    const float s = x * static_cast<float>(n);
    const int j = std::min(static_cast<int>(s), n - 1);
    const float f = s - static_cast<float>(j);
    const glm::dvec2 p = shape.points[static_cast<size_t>(j)] * (1.0 - f) + shape.points[static_cast<size_t>(j) + 1] * static_cast<double>(f);
    return vec3(std::cos(orientation) * static_cast<float>(p.x) / static_cast<float>(n),
                std::sin(orientation) * static_cast<float>(p.x) / static_cast<float>(n), static_cast<float>(p.y) / static_cast<float>(n));
  };
  BladeRest r;
  for (int i = 0; i < kBladeHinges; ++i) {
    r.hinge[i] = at(static_cast<float>(i) / kBladeHinges);
    r.centre[i] = at((static_cast<float>(i) + 0.5f) / kBladeHinges);
  }
  return r;
}

vegetation::BladeShape grassShape(float relativeStiffness) {
  const double kc = vegetation::criticalStiffness(vegetation::kBladeShapeSegments);
  auto shape = vegetation::solveBladeShape(relativeStiffness * kc, {.segments = vegetation::kBladeShapeSegments});
  EXPECT_TRUE(shape.ok());
  return shape.ok() ? *shape : vegetation::BladeShape{};
}

// Without wind the moments are 0 and the drawn blade is its rest shape exactly.
TEST(BladeResponse, NoWindKeepsTheRestShapeExactly) {
  const BladeRest r = restOf(grassShape(1.3f), 0.7f);
  BladeMoments m;
  for (int i = 0; i < kBladeHinges; ++i) m.m[i] = vec2(0.0f);
  const BladeBend b = solveBladeBend(r, m, 1.3f);
  for (int i = 0; i < kBladeHinges; ++i) EXPECT_EQ(length(b.hinge[i]), 0.0f);
  const vec3 tip = r.centre[3] * 1.0f;
  const vec3 moved = bendPoint(b, r, tip, 0.875f);
  EXPECT_EQ(moved.x, tip.x);
  EXPECT_EQ(moved.z, tip.z);
}

// A steady wind bends blades downwind, softer ones further (by angle: a drooping blade's low tip
// moves less for the same turn).
TEST(BladeResponse, WindBendsDownwindSofterBladesMore) {
  const VirtualBlade v = virtualBladeAtRest(vec3(8.0f, 0.0f, 0.0f));
  const BladeMoments m = virtualBladeMoments(v);
  float lastTurn = 0.0f;
  for (float s : {1.8f, 1.3f, 1.05f}) {
    const vegetation::BladeShape shape = grassShape(s);
    const BladeRest r = restOf(shape, 1.5707963f);  // leaning north, the wind from the west
    const BladeBend b = solveBladeBend(r, m, s);
    const vec3 tip(0.0f, static_cast<float>(shape.points.back().x) / 16.0f, static_cast<float>(shape.points.back().y) / 16.0f);
    const vec3 bent = bendPoint(b, r, tip, 1.0f);
    EXPECT_GT(bent.x, 0.05f) << "s = " << s;
    float turn = 0.0f;
    for (int i = 0; i < kBladeHinges; ++i) {
      EXPECT_GT(b.hinge[i].x, 0.0f) << "s = " << s << " hinge " << i;  // every hinge turns downwind
      turn += b.hinge[i].x;
    }
    EXPECT_GT(turn, lastTurn) << "s = " << s;
    lastTurn = turn;
  }
}

// After the response no blade tip is inside a static collider: 2 000 blades of random stiffness
// and orientation rooted within 1.2 m of a ball of radius 0.5 whose centre is 0.55 m up, and of a
// vertical capsule hovering 0.3 m above the ground.
TEST(BladeResponse, NoTipInsideAStaticCollider) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  std::vector<vegetation::BladeShape> shapes = {grassShape(1.05f), grassShape(1.3f), grassShape(1.8f)};
  for (int shapeCase = 0; shapeCase < 2; ++shapeCase) {
    SimulationParams sim{};
    sim.counts = ivec4(0, 1, kSimFlagInteraction, 1);
    if (shapeCase == 0)
      sim.colliders[0].centre = vec4(0.0f, 0.0f, 0.55f, 0.5f);  // camera-relative, the ground at z = 0
    else {
      sim.colliders[0].centre = vec4(0.0f, 0.0f, 1.1f, 0.4f);
      sim.colliders[0].shape = vec4(0.4f, 0.0f, 4.0f, 0.0f);
    }
    int inside = 0, turned = 0;
    for (int i = 0; i < 2000; ++i) {
      const float s = 1.05f + 0.75f * u01(rng);
      const vegetation::BladeShape& shape = shapes[static_cast<size_t>(i % 3)];
      const float orientation = 6.2831853f * u01(rng);
      const float rr = 1.2f * std::sqrt(u01(rng)), ra = 6.2831853f * u01(rng);
      const vec3 root(rr * std::cos(ra), rr * std::sin(ra), 0.0f);
      const float height = 0.3f + 0.6f * u01(rng);
      const BladeRest r = restOf(shape, orientation);
      BladeBend b;
      for (int k = 0; k < kBladeHinges; ++k) b.hinge[k] = vec2(0.0f);
      b.root = vec4(0.0f, 0.0f, 0.0f, 1.0f);
      const vec3 tipUnit = vec3(std::cos(orientation) * static_cast<float>(shape.points.back().x) / 16.0f,
                                std::sin(orientation) * static_cast<float>(shape.points.back().x) / 16.0f,
                                static_cast<float>(shape.points.back().y) / 16.0f);
      const vec3 tip = bendPoint(b, r, tipUnit, 1.0f) * height;
      b.root = colliderTurn(sim, root, tip, vec4(0.0f, 0.0f, 0.0f, 1.0f));
      if (b.root.w < 0.9999f) ++turned;
      const vec3 drawn = root + bendPoint(b, r, tipUnit, 1.0f) * height;
      const ColliderGpu& k = sim.colliders[0];
      if (colliderDistance(vec3(k.centre.x, k.centre.y, k.centre.z), k.centre.w, k.shape.x, drawn) < -1e-4f) {
        ++inside;
        ADD_FAILURE() << "root " << root.x << " " << root.y << " tip " << drawn.x << " " << drawn.y << " " << drawn.z
                      << " height " << height;
      }
      (void)s;
    }
    EXPECT_EQ(inside, 0) << "collider " << shapeCase;
    EXPECT_GT(turned, 100) << "collider " << shapeCase;  // the collider did reach many tips
  }
}

// The clock: whole sub-steps from time 0 whatever the frame times; a jump back restarts.
TEST(SimulationClock, CountsWholeSubstepsFromZero) {
  Simulation sim({.wind = {.speedMps = 5.0}});
  int64_t total = 0;
  for (int f = 0; f <= 60; ++f) {
    sim.step({.timeS = f / 60.0, .dtS = f ? 1.0 / 60.0 : 0.0});
    total += static_cast<int64_t>(sim.gpuStep().params.clock.x);
    EXPECT_TRUE(sim.gpuStep().runWind);
  }
  EXPECT_EQ(total, 240);
  EXPECT_EQ(sim.substeps(), 240);
  // A frame of a second runs at most kMaxSubsteps; the clock still ends at the frame's time.
  sim.step({.timeS = 2.0, .dtS = 1.0});
  EXPECT_EQ(sim.gpuStep().params.clock.x, static_cast<float>(kMaxSubsteps));
  EXPECT_EQ(sim.substeps(), 480);
  const int generation = sim.gpuStep().params.counts.w;
  sim.step({.timeS = 0.5});
  EXPECT_EQ(sim.gpuStep().params.counts.w, generation + 1);  // restarted: every blade at rest again
  // No wind, no colliders: nothing for the plants to read.
  Simulation calm;
  calm.step({.timeS = 0.0});
  EXPECT_EQ(calm.gpuStep().params.counts.z, 0);
  EXPECT_FALSE(calm.gpuStep().runWind);
}

}  // namespace
}  // namespace vegstream::simulation
