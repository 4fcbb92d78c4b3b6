// Colour scores, core seed ../shared/seeds/001_3eca9f2c7752e4fb.txt §3.3 eq. 16.
// Float arithmetic in the same order as shaders/common/colour_score.glsl.
#include "vegetation/colour_score.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace vegstream::vegetation {

float srgbEncode(float linear) {
  const float c = std::clamp(linear, 0.0f, 1.0f);
  return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

float srgbDecode(float encoded) {
  const float c = std::clamp(encoded, 0.0f, 1.0f);
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

glm::vec3 hsvFromSrgb(glm::vec3 c) {
  const float mx = std::max(c.r, std::max(c.g, c.b));
  const float mn = std::min(c.r, std::min(c.g, c.b));
  const float d = mx - mn;
  float h = 0.0f;
  if (d > 0.0f) {
    if (mx == c.r)
      h = (c.g - c.b) / d;
    else if (mx == c.g)
      h = 2.0f + (c.b - c.r) / d;
    else
      h = 4.0f + (c.r - c.g) / d;
    h /= 6.0f;
    if (h < 0.0f) h += 1.0f;
    if (h >= 1.0f) h -= 1.0f;  // −tiny + 1 rounds to 1
  }
  const float s = mx > 0.0f ? d / mx : 0.0f;
  return {h, s, mx};
}

glm::vec3 srgbFromHsv(glm::vec3 hsv) {
  const float h6 = hsv.x * 6.0f, c = hsv.z * hsv.y, x = c * (1.0f - std::abs(std::fmod(h6, 2.0f) - 1.0f));
  const glm::vec3 sectors[] = {{c, x, 0}, {x, c, 0}, {0, c, x}, {0, x, c}, {x, 0, c}, {c, 0, x}};
  return sectors[static_cast<int>(h6) % 6] + (hsv.z - c);
}

glm::vec3 hsvFromLinear(glm::vec3 linear) {
  return hsvFromSrgb({srgbEncode(linear.r), srgbEncode(linear.g), srgbEncode(linear.b)});
}

glm::vec3 hsvFromSrgb8(uint8_t r, uint8_t g, uint8_t b) {
  return hsvFromSrgb(glm::vec3(static_cast<float>(r), static_cast<float>(g), static_cast<float>(b)) / 255.0f);
}

float hueDistance(float a, float b) {
  const float d = std::abs(a - b);
  return std::min(d, 1.0f - d);
}

float weightedHsvDistance(glm::vec3 a, glm::vec3 b, glm::vec3 w) {
  const float dh = hueDistance(a.x, b.x) * w.x;
  const float ds = (a.y - b.y) * w.y;
  const float dv = (a.z - b.z) * w.z;
  return std::sqrt(dh * dh + ds * ds + dv * dv);
}

float weightedDistance(const ColourScoreParams& params, glm::vec3 hsv, float ndvi, float exg) {
  const float dh = hueDistance(params.reference.x, hsv.x) * params.weights.x;
  const float ds = (params.reference.y - hsv.y) * params.weights.y;
  const float dv = (params.reference.z - hsv.z) * params.weights.z;
  const float dn = hasNdvi(ndvi) ? (params.ndviReference - ndvi) * params.ndviWeight : 0.0f;
  const float de = hasExg(exg) ? (params.exgReference - exg) * params.exgWeight : 0.0f;
  return std::sqrt(dh * dh + ds * ds + dv * dv + dn * dn + de * de);
}

float logColourScore(const ColourScoreParams& params, glm::vec3 hsv, float ndvi, float exg) {
  const float dist = std::max(weightedDistance(params, hsv, ndvi, exg), kMinColourDistance);
  return -params.p * std::log(dist);
}

float colourScore(const ColourScoreParams& params, glm::vec3 hsv, float ndvi) {
  return std::exp(logColourScore(params, hsv, ndvi));
}

void blendWeights(std::span<const ColourScoreParams> types, glm::vec3 hsv, std::span<float> out, float ndvi) {
  assert(out.size() == types.size());
  if (types.empty()) return;
  float top = -INFINITY;
  for (size_t i = 0; i < types.size(); ++i) {
    out[i] = logColourScore(types[i], hsv, ndvi);
    top = std::max(top, out[i]);
  }
  float sum = 0.0f;
  for (float& w : out) {
    w = std::exp(w - top);  // the best type gets exp(0) = 1, so sum ≥ 1
    sum += w;
  }
  for (float& w : out) w /= sum;
}

std::vector<float> blendWeights(std::span<const ColourScoreParams> types, glm::vec3 hsv, float ndvi) {
  std::vector<float> out(types.size());
  blendWeights(types, hsv, out, ndvi);
  return out;
}

size_t bestMatch(std::span<const ColourScoreParams> types, glm::vec3 hsv, float ndvi) {
  assert(!types.empty());
  size_t best = 0;
  float bestScore = -INFINITY;
  for (size_t i = 0; i < types.size(); ++i) {
    const float s = logColourScore(types[i], hsv, ndvi);
    if (s > bestScore) {
      bestScore = s;
      best = i;
    }
  }
  return best;
}

}  // namespace vegstream::vegetation
