// SyntheticTerrain (synthetic_generator.h): the relief and biome colours of `vegstream
// generate`, as pure functions of the seed and a position in metres. Integer-lattice gradient
// noise with a hash of (cell, seed), so nothing depends on the order of evaluation or on threads.

#include <algorithm>
#include <array>
#include <cmath>

#include "core/hash.h"
#include "datasets/synthetic_generator.h"

namespace vegstream::datasets {
namespace {

uint32_t hashCell(int64_t ix, int64_t iy, uint32_t seed) {
  uint32_t h = mix32(static_cast<uint32_t>(ix) ^ seed);
  h = mix32(h ^ static_cast<uint32_t>(iy) * 0x9e3779b9U);
  return mix32(h + static_cast<uint32_t>(ix >> 32) * 0x85ebca6bU + static_cast<uint32_t>(iy >> 32));
}

double quintic(double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }

// 2-D gradient noise, about −1 … 1, zero at lattice points.
double gradientNoise(double x, double y, uint32_t seed) {
  const double fx = std::floor(x), fy = std::floor(y);
  const auto ix = static_cast<int64_t>(fx), iy = static_cast<int64_t>(fy);
  const double dx = x - fx, dy = y - fy;
  // 16 gradient directions, evenly spread (cos, sin of k·22.5°).
  static constexpr double kGx[16] = {1.0,  0.92388,  0.70711,  0.38268,  0.0, -0.38268, -0.70711, -0.92388,
                                     -1.0, -0.92388, -0.70711, -0.38268, 0.0, 0.38268,  0.70711,  0.92388};
  auto corner = [&](int64_t cx, int64_t cy, double ox, double oy) {
    const uint32_t k = hashCell(ix + cx, iy + cy, seed) & 15U;
    return kGx[k] * ox + kGx[(k + 12U) & 15U] * oy;
  };
  const double n00 = corner(0, 0, dx, dy), n10 = corner(1, 0, dx - 1.0, dy);
  const double n01 = corner(0, 1, dx, dy - 1.0), n11 = corner(1, 1, dx - 1.0, dy - 1.0);
  const double u = quintic(dx), v = quintic(dy);
  const double nx0 = n00 + u * (n10 - n00), nx1 = n01 + u * (n11 - n01);
  return 1.41 * (nx0 + v * (nx1 - nx0));
}

// The next octave's point: doubled in frequency (×2 in scale) and rotated, so that lattice
// artefacts of successive octaves do not line up.
void nextOctave(double& x, double& y) {
  const double rx = 1.6 * x + 1.2 * y, ry = -1.2 * x + 1.6 * y;
  x = rx;
  y = ry;
}

double fbm(double x, double y, int octaves, uint32_t seed) {
  double sum = 0.0, amp = 0.5, norm = 0.0;
  for (int o = 0; o < octaves; ++o) {
    sum += amp * gradientNoise(x, y, seed + static_cast<uint32_t>(o) * 0x632be5abU);
    norm += amp;
    nextOctave(x, y);
    amp *= 0.5;
  }
  return sum / norm;
}

// Ridged multifractal (Musgrave): sharp crests where the noise crosses zero, rougher where a
// coarser octave already made a ridge. 0 … ~1.
double ridged(double x, double y, int octaves, uint32_t seed) {
  double sum = 0.0, amp = 0.5, weight = 1.0, norm = 0.0;
  for (int o = 0; o < octaves; ++o) {
    double r = 1.0 - std::abs(gradientNoise(x, y, seed + static_cast<uint32_t>(o) * 0x2545f491U));
    r *= r;
    r *= weight;
    weight = std::clamp(r * 2.0, 0.0, 1.0);
    sum += amp * r;
    norm += amp;
    nextOctave(x, y);
    amp *= 0.5;
  }
  return sum / norm;
}

double smoothstep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

using Rgb = std::array<double, 3>;
Rgb lerp(const Rgb& a, const Rgb& b, double t) {
  return {a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t, a[2] + (b[2] - a[2]) * t};
}

constexpr double kReliefWavelengthM = 9000.0;  // size of the largest mountains
constexpr double kValleyFloorM = 700.0;
constexpr double kDeg = M_PI / 180.0;

}  // namespace

SyntheticTerrain::SyntheticTerrain(uint64_t seed) {
  uint32_t s = mix32(static_cast<uint32_t>(seed) ^ mix32(static_cast<uint32_t>(seed >> 32) + 0x1234567U));
  for (auto& v : seed_) {
    s = mix32(s + 0x9e3779b9U);
    v = s;
  }
}

double SyntheticTerrain::heightM(double eastM, double northM) const {
  const double px = eastM / kReliefWavelengthM, py = northM / kReliefWavelengthM;
  // Domain warp: bends ridges and valleys so they do not follow the noise lattice.
  const double wx = px + 0.25 * fbm(px + 5.2, py + 1.3, 3, seed_[0]);
  const double wy = py + 0.25 * fbm(px + 1.7, py + 9.2, 3, seed_[1]);
  const double region = fbm(0.6 * wx, 0.6 * wy, 3, seed_[2]);  // −1 … 1: valley … massif
  const double mountains = smoothstep(-0.45, 0.35, region);
  const double ridges = ridged(1.3 * wx, 1.3 * wy, 7, seed_[3]);          // 0 … 1
  const double hills = fbm(3.0 * wx, 3.0 * wy, 5, seed_[2] ^ 0xabcdefU);  // rolling valley floor
  return kValleyFloorM + 250.0 * (region + 1.0) + 60.0 * hills + 2600.0 * mountains * std::pow(ridges, 1.6);
}

std::array<uint8_t, 3> SyntheticTerrain::color(double eastM, double northM, double h, double slopeRad) const {
  // Chosen so that the default species catalog (config/species.json, whose references are read
  // off muted Landsat imagery) grows what each biome is: grass on the valley and alpine meadows
  // (olive, HSV ≈ 85°, 0.38, 0.4), conifers in the forest (very dark green, v 0.13), nothing on rock,
  // scree and snow (greys: the bare "grey rock" entry) — `vegstream plants` shows the shares.
  static constexpr Rgb kGrass{85, 102, 63}, kForest{24, 34, 20}, kMeadow{88, 104, 66}, kRock{112, 110, 108},
      kScree{140, 138, 134}, kSnow{238, 241, 246};
  const double patch = fbm(eastM / 350.0, northM / 350.0, 4, seed_[0] ^ 0x5a5a5aU);  // −1 … 1
  const double detail = fbm(eastM / 40.0, northM / 40.0, 2, seed_[1] ^ 0xa5a5a5U);
  const double treeLine = 1900.0 + 120.0 * patch;
  const double snowLine = 2750.0 + 150.0 * patch;
  const double slopeDeg = slopeRad / kDeg;

  // Valleys: grass with forest patches that thicken up the lower slopes.
  const double forest = smoothstep(-0.15, 0.15, patch + 0.6 * smoothstep(kValleyFloorM + 200.0, 1300.0, h) - 0.3);
  Rgb c = lerp(kGrass, kForest, forest);
  c = lerp(c, kMeadow, smoothstep(treeLine - 120.0, treeLine + 120.0, h));
  c = lerp(c, kScree, smoothstep(treeLine + 300.0, treeLine + 700.0, h) * 0.6);
  c = lerp(c, kRock, smoothstep(30.0, 42.0, slopeDeg + 6.0 * detail));
  c = lerp(c, kSnow, smoothstep(snowLine - 80.0, snowLine + 80.0, h) * (1.0 - smoothstep(38.0, 52.0, slopeDeg)));
  std::array<uint8_t, 3> out{};
  const double shade = 1.0 + 0.06 * detail;
  for (size_t i = 0; i < 3; ++i) out[i] = static_cast<uint8_t>(std::lround(std::clamp(c[i] * shade, 0.0, 255.0)));
  return out;
}

}  // namespace vegstream::datasets
