#pragma once
// The sRGB transfer curve, IEC 61966-2-1:1999 (§5.2): the piecewise curve of the standard
// (linear segment below 0.0031308 / 0.04045, then exponent 2.4 with offset 0.055), not a plain
// gamma. The imagery tiles hold albedo sRGB-encoded, and the GPU samples them through an sRGB
// format, so these two are the import's half of that contract.

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace vegstream::datasets {

// Linear 0 … 1 → encoded 0 … 1 (clamped).
inline float srgbEncode(float linear) {
  const float l = std::clamp(linear, 0.0f, 1.0f);
  return l <= 0.0031308f ? 12.92f * l : 1.055f * std::pow(l, 1.0f / 2.4f) - 0.055f;
}

// Encoded 0 … 1 → linear 0 … 1 (clamped).
inline float srgbDecode(float encoded) {
  const float e = std::clamp(encoded, 0.0f, 1.0f);
  return e <= 0.04045f ? e / 12.92f : std::pow((e + 0.055f) / 1.055f, 2.4f);
}

// Linear 0 … 1 → the nearest 8-bit code.
inline uint8_t srgbEncode8(float linear) { return static_cast<uint8_t>(std::lround(srgbEncode(linear) * 255.0f)); }

}  // namespace vegstream::datasets
