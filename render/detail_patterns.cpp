#include "render/detail_patterns.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>

#include "core/hash.h"

namespace vegstream::render {
namespace {

using vegetation::DetailSurface;
constexpr float kTau = 6.28318530718f;

uint32_t hash(uint32_t x, uint32_t y, uint32_t seed) {
  return mix32(x * 0x8da6b343u ^ y * 0xd8163841u ^ (seed + 1u) * 0xcb1ab31fu);
}

float rand01(uint32_t x, uint32_t y, uint32_t seed) { return static_cast<float>(hash(x, y, seed) >> 8) / 16777216.0f; }

uint32_t wrap(int i, int period) { return static_cast<uint32_t>(((i % period) + period) % period); }

float fade(float t) { return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f); }

// Value noise over a lattice of px × py cells across the unit square, wrapping at its edges;
// u, v in [0, 1). Result in [0, 1].
float valueNoise(float u, float v, int px, int py, uint32_t seed) {
  const float x = u * static_cast<float>(px), y = v * static_cast<float>(py);
  const float fx = std::floor(x), fy = std::floor(y);
  const int xi = static_cast<int>(fx), yi = static_cast<int>(fy);
  const float tx = fade(x - fx), ty = fade(y - fy);
  const uint32_t x0 = wrap(xi, px), x1 = wrap(xi + 1, px), y0 = wrap(yi, py), y1 = wrap(yi + 1, py);
  const float a = rand01(x0, y0, seed), b = rand01(x1, y0, seed);
  const float c = rand01(x0, y1, seed), d = rand01(x1, y1, seed);
  return (a + (b - a) * tx) + ((c + (d - c) * tx) - (a + (b - a) * tx)) * ty;
}

// Fractal sum of `octaves` value noises from px × py cells up, each octave twice as fine and
// half as strong; normalised to [0, 1].
float fbm(float u, float v, int px, int py, int octaves, uint32_t seed) {
  float sum = 0.0f, amp = 1.0f, norm = 0.0f;
  for (int o = 0; o < octaves; ++o) {
    sum += amp * valueNoise(u, v, px << o, py << o, seed + static_cast<uint32_t>(o) * 101u);
    norm += amp;
    amp *= 0.5f;
  }
  return sum / norm;
}

using Texel = std::array<float, 3>;

// Grass seen from above: short tapering blades, four rooted in each cell of a 20 × 20 grid at
// random spots, angles and lengths (at most one cell, so the 3 × 3 cells around a texel hold
// every blade that can cover it), lighter towards the tip, some drier (yellower), over dark
// shadowed ground.
Texel grass(float u, float v) {
  constexpr int kCells = 20;
  const float x = u * kCells, y = v * kCells;
  const int cx = static_cast<int>(std::floor(x)), cy = static_cast<int>(std::floor(y));
  const float ground = 0.22f + 0.18f * fbm(u, v, 16, 16, 3, 16);
  Texel colour{ground, ground, ground};
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const uint32_t i = wrap(cx + dx, kCells), j = wrap(cy + dy, kCells);
      for (uint32_t b = 0; b < 4; ++b) {
        const uint32_t seed = 100u + 10u * b;
        const float rx = static_cast<float>(cx + dx) + rand01(i, j, seed);
        const float ry = static_cast<float>(cy + dy) + rand01(i, j, seed + 1);
        const float angle = kTau * rand01(i, j, seed + 2);
        const float length = 0.5f + 0.5f * rand01(i, j, seed + 3);
        const float ex = std::cos(angle), ey = std::sin(angle);
        const float t = std::clamp(((x - rx) * ex + (y - ry) * ey) / length, 0.0f, 1.0f);
        const float d = std::hypot(x - (rx + ex * t * length), y - (ry + ey * t * length));
        const float width = 0.085f * (1.0f - 0.75f * t);
        const float cover = std::clamp(1.5f - d / width, 0.0f, 1.0f);  // soft edge
        if (cover <= 0.0f) continue;
        const float bright = (0.55f + 0.35f * rand01(i, j, seed + 4)) * (0.75f + 0.35f * t);
        const float dry = rand01(i, j, seed + 5) < 0.2f ? 1.0f : 0.0f;
        const Texel blade{bright * (1.0f + 0.25f * dry), bright, bright * (1.0f - 0.3f * dry)};
        for (size_t c = 0; c < 3; ++c) colour[c] += (blade[c] - colour[c]) * cover;
      }
    }
  return colour;
}

// Sandstone: horizontal strata bent by noise, a grain, and dark ridged cracks.
Texel rock(float u, float v) {
  const float warp = fbm(u, v, 3, 3, 3, 21);
  const float strata = 0.5f + 0.5f * std::sin(kTau * (6.0f * v + 1.5f * warp));
  const float grain = fbm(u, v, 48, 48, 3, 22);
  const float ridged = 1.0f - std::abs(2.0f * fbm(u, v, 5, 5, 4, 23) - 1.0f);
  const float crack = std::clamp((ridged - 0.9f) / 0.08f, 0.0f, 1.0f);
  const float value = (0.45f + 0.35f * strata + 0.4f * grain) * (1.0f - 0.75f * crack);
  return {value * (1.0f + 0.08f * strata), value, value * (1.0f - 0.08f * strata)};
}

// Pebbles: one per cell of a 32 × 32 grid, at a random spot, of random size, brightness and
// tint, shaded darker towards the rim; soil between them with a fine speckle.
Texel gravel(float u, float v) {
  constexpr int kCells = 32;
  const float x = u * kCells, y = v * kCells;
  const int cx = static_cast<int>(std::floor(x)), cy = static_cast<int>(std::floor(y));
  float best = 0.0f;  // height of the highest pebble covering the texel (0: soil)
  Texel colour{0.0f, 0.0f, 0.0f};
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const uint32_t i = wrap(cx + dx, kCells), j = wrap(cy + dy, kCells);
      const float px = static_cast<float>(cx + dx) + rand01(i, j, 31);
      const float py = static_cast<float>(cy + dy) + rand01(i, j, 32);
      const float radius = 0.3f + 0.35f * rand01(i, j, 33);
      const float d = std::hypot(x - px, y - py) / radius;
      if (d >= 1.0f) continue;
      const float height = std::sqrt(1.0f - d * d) * radius;
      if (height <= best) continue;
      best = height;
      const float bright = (0.45f + 0.55f * rand01(i, j, 34)) * (0.65f + 0.35f * std::sqrt(1.0f - d * d));
      const float tint = rand01(i, j, 35) - 0.5f;
      colour = {bright * (1.0f + 0.2f * tint), bright, bright * (1.0f - 0.2f * tint)};
    }
  const float speckle = fbm(u, v, 128, 128, 1, 36);
  if (best == 0.0f) {
    const float soil = 0.25f + 0.25f * speckle;
    return {soil, soil, soil};
  }
  for (float& c : colour) c *= 0.85f + 0.3f * speckle;
  return colour;
}

// Wind ripples: asymmetric waves (gentle stoss side, steep lee side), bent by noise, with a
// fine sand grain.
Texel sand(float u, float v) {
  const float phase = 24.0f * u + 2.5f * fbm(u, v, 2, 3, 3, 41);
  const float f = phase - std::floor(phase);
  const float profile = f < 0.75f ? f / 0.75f : (1.0f - f) / 0.25f;
  const float grain = fbm(u, v, 128, 128, 1, 42);
  const float value = 0.45f + 0.35f * profile + 0.25f * grain;
  return {value, value, value};
}

Texel patternAt(DetailSurface surface, float u, float v) {
  switch (surface) {
    case DetailSurface::Grass: return grass(u, v);
    case DetailSurface::Rock: return rock(u, v);
    case DetailSurface::Gravel: return gravel(u, v);
    case DetailSurface::Sand: return sand(u, v);
  }
  return {0.5f, 0.5f, 0.5f};
}

// Contrast of each surface's modulation: standard deviation around the mean 0.5.
float contrast(DetailSurface surface) {
  switch (surface) {
    case DetailSurface::Grass: return 0.17f;
    case DetailSurface::Rock: return 0.14f;
    case DetailSurface::Gravel: return 0.18f;
    case DetailSurface::Sand: return 0.09f;
  }
  return 0.1f;
}

}  // namespace

std::vector<uint8_t> generateDetailPattern(DetailSurface surface, uint32_t size) {
  assert(size >= 16 && (size & (size - 1)) == 0);
  const size_t n = size_t{size} * size;
  std::vector<float> values(n * 3);
  for (uint32_t y = 0; y < size; ++y)
    for (uint32_t x = 0; x < size; ++x) {
      const float u = (static_cast<float>(x) + 0.5f) / static_cast<float>(size);
      const float v = (static_cast<float>(y) + 0.5f) / static_cast<float>(size);
      const Texel t = patternAt(surface, u, v);
      std::copy(t.begin(), t.end(), values.begin() + static_cast<std::ptrdiff_t>((size_t{y} * size + x) * 3));
    }
  std::vector<uint8_t> out(n * 4, 255);
  for (size_t c = 0; c < 3; ++c) {
    double mean = 0.0, square = 0.0;
    for (size_t i = 0; i < n; ++i) mean += values[i * 3 + c];
    mean /= static_cast<double>(n);
    for (size_t i = 0; i < n; ++i) square += (values[i * 3 + c] - mean) * (values[i * 3 + c] - mean);
    const double sigma = std::max(std::sqrt(square / static_cast<double>(n)), 1e-6);
    const double scale = contrast(surface) / sigma;
    for (size_t i = 0; i < n; ++i) {
      const double m = std::clamp(0.5 + (values[i * 3 + c] - mean) * scale, 0.0, 1.0);
      out[i * 4 + c] = static_cast<uint8_t>(std::lround(m * 255.0));
    }
  }
  return out;
}

uint32_t mipLevelCount(uint32_t size) {
  uint32_t levels = 1;
  while (size > 1) {
    size /= 2;
    ++levels;
  }
  return levels;
}

std::vector<uint8_t> withMipChain(const std::vector<uint8_t>& level0, uint32_t size) {
  assert(level0.size() == size_t{size} * size * 4);
  std::vector<uint8_t> out(level0);
  size_t previous = 0;  // offset of the level being halved
  for (uint32_t s = size; s > 1; s /= 2) {
    const uint32_t h = s / 2;
    const size_t start = out.size();
    out.resize(start + size_t{h} * h * 4);
    for (uint32_t y = 0; y < h; ++y)
      for (uint32_t x = 0; x < h; ++x)
        for (size_t c = 0; c < 4; ++c) {
          auto at = [&](uint32_t xx, uint32_t yy) { return unsigned{out[previous + (size_t{yy} * s + xx) * 4 + c]}; };
          const unsigned sum =
              at(2 * x, 2 * y) + at(2 * x + 1, 2 * y) + at(2 * x, 2 * y + 1) + at(2 * x + 1, 2 * y + 1);
          out[start + (size_t{y} * h + x) * 4 + c] = static_cast<uint8_t>((sum + 2) / 4);
        }
    previous = start;
  }
  return out;
}

const std::vector<uint8_t>& detailTextureData() {
  static const std::vector<uint8_t> data = [] {
    std::vector<uint8_t> all;
    for (uint32_t s = 0; s < vegetation::kDetailSurfaceCount; ++s) {
      const auto layer =
          withMipChain(generateDetailPattern(static_cast<DetailSurface>(s), kDetailTextureSize), kDetailTextureSize);
      all.insert(all.end(), layer.begin(), layer.end());
    }
    return all;
  }();
  return data;
}

}  // namespace vegstream::render
