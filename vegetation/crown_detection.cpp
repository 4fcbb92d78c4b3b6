// Tree tops of a canopy height model by local maxima in a height-dependent window
// (crown_detection.h; Popescu & Wynne 2004, PE&RS 70(5), "local filtering with variable window size").

#include "vegetation/crown_detection.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace vegstream::vegetation {
namespace {

struct Grid {
  std::span<const float> v;
  int w = 0, h = 0;
  bool inside(int x, int y) const { return x >= 0 && y >= 0 && x < w && y < h; }
  float at(int x, int y) const { return v[size_t(y) * size_t(w) + size_t(x)]; }
};

// 3 × 3 binomial low-pass over the valid neighbours within kSmoothingStepM of the centre (a
// no-data pixel stays no data): noise goes, but a tall neighbour's crown edge does not leak into
// a small crown beside it.
constexpr float kSmoothingStepM = 1.0f;
// A higher pixel beyond a dip of kValleyM + kValleyShare × the top's height is another crown's.
constexpr float kValleyM = 0.3f;
constexpr float kValleyShare = 0.0f;

std::vector<float> smoothed(const Grid& g) {
  static constexpr float kWeight[3] = {1.0f, 2.0f, 1.0f};
  std::vector<float> out(g.v.size(), NAN);
  for (int y = 0; y < g.h; ++y)
    for (int x = 0; x < g.w; ++x) {
      if (std::isnan(g.at(x, y))) continue;
      float sum = 0.0f, weight = 0.0f;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          if (!g.inside(x + dx, y + dy)) continue;
          const float s = g.at(x + dx, y + dy);
          if (std::isnan(s) || std::abs(s - g.at(x, y)) > kSmoothingStepM) continue;
          const float k = kWeight[dx + 1] * kWeight[dy + 1];
          sum += k * s;
          weight += k;
        }
      out[size_t(y) * size_t(g.w) + size_t(x)] = sum / weight;
    }
  return out;
}

// Whether the straight way from (x, y) to (x + dx, y + dy) dips more than the valley depth below
// the start: then the higher pixel there stands on another crown.
bool acrossValley(const Grid& s, int x, int y, int dx, int dy, float start) {
  const int steps = std::max(std::abs(dx), std::abs(dy));
  const float floor = start - (kValleyM + kValleyShare * start);
  for (int k = 1; k < steps; ++k) {
    const int px = x + static_cast<int>(std::lround(double(dx) * k / steps));
    const int py = y + static_cast<int>(std::lround(double(dy) * k / steps));
    const float v = s.at(px, py);
    if (std::isnan(v) || v < floor) return true;
  }
  return false;
}

// Whether (x, y) beats every pixel of its window on its own crown: none higher, none equal and
// earlier (row-major), unless a valley lies between them.
bool isTop(const Grid& s, int x, int y, float radiusPx) {
  const float c = s.at(x, y);
  const int r = static_cast<int>(std::floor(radiusPx));
  const float r2 = radiusPx * radiusPx;
  for (int dy = -r; dy <= r; ++dy)
    for (int dx = -r; dx <= r; ++dx) {
      if ((dx == 0 && dy == 0) || float(dx * dx + dy * dy) > r2 || !s.inside(x + dx, y + dy)) continue;
      const float q = s.at(x + dx, y + dy);
      const bool beats = q > c || (q == c && (dy < 0 || (dy == 0 && dx < 0)));
      if (beats && !acrossValley(s, x, y, dx, dy, c)) return false;
    }
  return true;
}

// The vertex of the parabola through (−1, a), (0, b), (1, c), within ±0.5.
double vertexOffset(float a, float b, float c) {
  if (std::isnan(a) || std::isnan(c)) return 0.0;
  const double d = double(a) - 2.0 * double(b) + double(c);
  if (!(d < 0.0)) return 0.0;
  return std::clamp(0.5 * (double(a) - double(c)) / d, -0.5, 0.5);
}

float sampleOr(const Grid& g, int x, int y, float fallback) { return g.inside(x, y) ? g.at(x, y) : fallback; }

// The crown's radius: the mean of the walks down its 8 directions (crown_detection.h).
float crownRadius(const Grid& s, int x, int y, float heightM, const CrownDetectionOptions& o, int maxSteps) {
  static constexpr int kDir[8][2] = {{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}};
  const float floor = std::max(o.minHeightM, kCrownFloor * heightM);
  float sum = 0.0f;
  for (const auto& d : kDir) {
    float prev = s.at(x, y);
    int k = 1;
    for (; k <= maxSteps; ++k) {
      const int px = x + k * d[0], py = y + k * d[1];
      if (!s.inside(px, py)) break;
      const float v = s.at(px, py);
      if (std::isnan(v) || v > prev || v < floor) break;
      prev = v;
    }
    const float step = (d[0] != 0 && d[1] != 0) ? 1.41421356f : 1.0f;
    sum += (float(k) - 0.5f) * step;
  }
  return sum / 8.0f * o.pixelM;
}

DetectedCrown crownAt(const Grid& raw, const Grid& s, int x, int y, const CrownDetectionOptions& o) {
  DetectedCrown c;
  const float centre = s.at(x, y);
  c.col = x + 0.5 + vertexOffset(sampleOr(s, x - 1, y, NAN), centre, sampleOr(s, x + 1, y, NAN));
  c.row = y + 0.5 + vertexOffset(sampleOr(s, x, y - 1, NAN), centre, sampleOr(s, x, y + 1, NAN));
  float top = raw.at(x, y);
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const float v = sampleOr(raw, x + dx, y + dy, NAN);
      if (!std::isnan(v) && std::abs(v - raw.at(x, y)) <= kSmoothingStepM) top = std::max(top, v);
    }
  c.heightM = top;
  const float window = windowRadiusM(o, top);
  const int maxSteps = static_cast<int>(std::ceil(2.0f * window / o.pixelM));
  c.crownRadiusM = std::clamp(crownRadius(s, x, y, top, o, maxSteps), o.pixelM, 2.0f * window);
  return c;
}

}  // namespace

float popescuWynneCrownWidthM(float heightM) { return 2.51503f + 0.00901f * heightM * heightM; }

float windowRadiusM(const CrownDetectionOptions& o, float heightM) {
  return std::clamp(0.5f * o.windowScale * popescuWynneCrownWidthM(heightM), o.minWindowM, o.maxWindowM);
}

int marginPixels(const CrownDetectionOptions& o) {
  return static_cast<int>(std::ceil(2.0f * windowRadiusM(o, o.maxHeightM) / o.pixelM)) + 3;
}

std::vector<DetectedCrown> detectCrowns(std::span<const float> heights, int width, int height,
                                        const CrownDetectionOptions& options) {
  assert(options.pixelM > 0.0f && heights.size() == size_t(width) * size_t(height));
  const Grid raw{heights, width, height};
  const std::vector<float> smooth = smoothed(raw);
  const Grid s{smooth, width, height};
  std::vector<DetectedCrown> out;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const float c = s.at(x, y);
      if (!(c >= options.minHeightM)) continue;
      const float h = std::min(c, options.maxHeightM);
      if (!isTop(s, x, y, windowRadiusM(options, h) / options.pixelM)) continue;
      out.push_back(crownAt(raw, s, x, y, options));
    }
  return out;
}

}  // namespace vegstream::vegetation
