// Colour scores, core seed ../shared/seeds/001_3eca9f2c7752e4fb.txt §3.3 eq. 16:
// s = ‖(r − b) ⊙ w‖^(−p) in HSV with the hue difference wrapped around the colour circle.
// The GLSL twin of vegetation/colour_score.h/.cpp, operation for operation (keep them in step;
// tests/render/colour_score_gpu_test.cpp compares the two). Conventions as there: RGB in
// [0, 1]; HSV from sRGB-encoded components, h in [0, 1) (0 red, 1/3 green), s, v in [0, 1].

const float kMinColourDistance = 1e-4;

float srgbEncode(float linear) {
  float c = clamp(linear, 0.0, 1.0);
  return c <= 0.0031308 ? 12.92 * c : 1.055 * pow(c, 1.0 / 2.4) - 0.055;
}

float srgbDecode(float encoded) {
  float c = clamp(encoded, 0.0, 1.0);
  return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

vec3 srgbEncode(vec3 linear) { return vec3(srgbEncode(linear.r), srgbEncode(linear.g), srgbEncode(linear.b)); }

vec3 hsvFromSrgb(vec3 c) {
  float mx = max(c.r, max(c.g, c.b));
  float mn = min(c.r, min(c.g, c.b));
  float d = mx - mn;
  float h = 0.0;
  if (d > 0.0) {
    if (mx == c.r)
      h = (c.g - c.b) / d;
    else if (mx == c.g)
      h = 2.0 + (c.b - c.r) / d;
    else
      h = 4.0 + (c.r - c.g) / d;
    h /= 6.0;
    if (h < 0.0) h += 1.0;
    if (h >= 1.0) h -= 1.0;
  }
  float s = mx > 0.0 ? d / mx : 0.0;
  return vec3(h, s, mx);
}

vec3 hsvFromLinear(vec3 linear) { return hsvFromSrgb(srgbEncode(linear)); }

// min(|a − b|, 1 − |a − b|) for hues in [0, 1].
float hueDistance(float a, float b) {
  float d = abs(a - b);
  return min(d, 1.0 - d);
}

// ‖(Δh, Δs, Δv) ⊙ w‖ with the wrapped hue difference.
float weightedHsvDistance(vec3 a, vec3 b, vec3 w) {
  float dh = hueDistance(a.x, b.x) * w.x;
  float ds = (a.y - b.y) * w.y;
  float dv = (a.z - b.z) * w.z;
  return sqrt(dh * dh + ds * ds + dv * dv);
}

// ln s = −p · ln max(distance, kMinColourDistance). Blend weights s_i / Σ s are formed from
// these as exp(ln s_i − max ln s) / Σ exp(ln s_j − max ln s), which cannot overflow.
float logColourScore(vec3 reference, vec3 weights, float p, vec3 hsv) {
  float dist = max(weightedHsvDistance(reference, hsv, weights), kMinColourDistance);
  return -p * log(dist);
}

// NDVI as a fourth channel (colour_score.h): ndviRefWeight = (reference, weight); an ndvi below
// −1.5 (kNoNdvi) means none there, and the term is 0 — the same float result as without it.
const float kNoNdvi = -2.0;

// An NDVI byte as an R8 UNORM texel holds it (datasets/tile_codec.h ndviFromByte: 0 = none).
float ndviOfTexel(float unorm) {
  uint b = uint(unorm * 255.0 + 0.5);
  return b == 0u ? kNoNdvi : (float(b) - 128.0) / 127.0;
}

float logColourScore(vec3 reference, vec3 weights, float p, vec2 ndviRefWeight, vec3 hsv, float ndvi) {
  float dh = hueDistance(reference.x, hsv.x) * weights.x;
  float ds = (reference.y - hsv.y) * weights.y;
  float dv = (reference.z - hsv.z) * weights.z;
  float dn = ndvi >= -1.5 ? (ndviRefWeight.x - ndvi) * ndviRefWeight.y : 0.0;
  float dist = max(sqrt(dh * dh + ds * ds + dv * dv + dn * dn), kMinColourDistance);
  return -p * log(dist);
}

// With the excess-green term too (colour_score.h; exgRefWeight = (reference, weight); an exg
// below −1.5 means none given): the sum in the CPU's order, dn² then de².
float logColourScore(vec3 reference, vec3 weights, float p, vec2 ndviRefWeight, vec2 exgRefWeight, vec3 hsv,
                     float ndvi, float exg) {
  float dh = hueDistance(reference.x, hsv.x) * weights.x;
  float ds = (reference.y - hsv.y) * weights.y;
  float dv = (reference.z - hsv.z) * weights.z;
  float dn = ndvi >= -1.5 ? (ndviRefWeight.x - ndvi) * ndviRefWeight.y : 0.0;
  float de = exg >= -1.5 ? (exgRefWeight.x - exg) * exgRefWeight.y : 0.0;
  float dist = max(sqrt(dh * dh + ds * ds + dv * dv + dn * dn + de * de), kMinColourDistance);
  return -p * log(dist);
}

float colourScore(vec3 reference, vec3 weights, float p, vec3 hsv) {
  return exp(logColourScore(reference, weights, p, hsv));
}
