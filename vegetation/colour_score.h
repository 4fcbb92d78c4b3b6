#pragma once
// Colour scores: how well a base colour (the imagery under a point) matches a reference colour.
// Core seed ../shared/seeds/001_3eca9f2c7752e4fb.txt §3.3, eq. 16:
//
//     s_i = ‖(r_i − b) ⊙ w_i‖^(−p_i)
//
// r_i: the reference colour of type i (HSV), b: the base colour (HSV), w_i: per-channel weights
// (a weight of 0 ignores a channel, e.g. the hue of grey rock or the value that shadows change),
// p_i: the exponent that sets how sharp transitions between types are. The hue difference wraps
// around: Δh = min(|h_r − h_b|, 1 − |h_r − h_b|) for hues in [0, 1), so hue 0.95 and 0.05 are 0.1
// apart. The distance is clamped to kMinColourDistance before the power, so a base colour equal
// to a reference gives a large finite score instead of a division by zero.
//
// Near-infrared (issue 18): a dataset imported with `--imagery-nir` also has the NDVI under each
// point, (NIR − red) / (NIR + red) in −1 … 1, and the distance gains a fourth term,
// (n_i − n_b) · w_n,i: living plants reflect near-infrared strongly (NDVI 0.3 … 0.5 on the Zion
// Landsat digital numbers), rock and shadowed rock do not (0.05 … 0.2), so a dark rock face stops
// looking like dark forest. Where there is no NDVI (kNoNdvi, or NaN) the term is 0: datasets
// without near-infrared score exactly as before.
//
// Excess green (issue 41): the ExG of the calibrated colour (colour_calibration.h), −1 … 2, gives
// a fifth term (e_i − e_b) · w_e,i, so green vegetation is told from grey and red ground by an
// index that colour casts do not move, with or without near-infrared. Callers that pass only HSV
// (kNoExg) get no term: the score as before.
//
// Blend weights over a set of types are s_i / Σ_j s_j, computed as exp(ln s_i − max ln s) /
// Σ exp(ln s_j − max ln s): the same numbers without overflow for large p.
//
// Colour conventions: RGB components in [0, 1]. "sRGB" means gamma-encoded as 8-bit imagery
// stores it; "linear" means what an sRGB texture sampler returns. HSV is always computed from the
// sRGB-encoded components (the way people pick reference colours from a photo): h in [0, 1)
// (0 red, 1/3 green, 2/3 blue; 0 for greys), s and v in [0, 1].
//
// shaders/common/colour_score.glsl is the same maths in GLSL, operation for operation, so GPU
// and CPU agree to float precision (tests/render/colour_score_gpu_test.cpp checks it). General
// on purpose: the terrain detail textures (vegetation/terrain_types.h) and the species catalog
// both score colours through ColourScoreParams.

#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

namespace vegstream::vegetation {

// One colour score's parameters (eq. 16).
struct ColourScoreParams {
  glm::vec3 reference{0.0f};  // HSV: x hue [0, 1), y saturation, z value
  glm::vec3 weights{1.0f};    // per channel (h, s, v), ≥ 0
  float p = 2.0f;             // exponent, > 0
  float ndviReference = 0.0f; // the NDVI the type grows on (−1 … 1)
  float ndviWeight = 0.0f;    // ≥ 0; 0 ignores NDVI
  float exgReference = 0.0f;  // the excess green the type grows on (−1 … 2)
  float exgWeight = 0.0f;     // ≥ 0; 0 ignores it
};

// "No NDVI here" (any value below −1.5, and NaN, means the same). The GLSL twin uses the same
// number, because a shader cannot rely on NaN.
inline constexpr float kNoNdvi = -2.0f;
inline bool hasNdvi(float ndvi) { return ndvi >= -1.5f; }
// "No excess green given" (ExG is ≥ −1): the term is 0.
inline constexpr float kNoExg = -2.0f;
inline bool hasExg(float exg) { return exg >= -1.5f; }

// Distances below this are treated as this (score (1e-4)^−p instead of infinity).
inline constexpr float kMinColourDistance = 1e-4f;

// The sRGB transfer function, one component (IEC 61966-2-1).
float srgbEncode(float linear);
float srgbDecode(float encoded);

// HSV of sRGB-encoded components in [0, 1] (hexcone model; hue 0 and saturation 0 for greys
// and black).
glm::vec3 hsvFromSrgb(glm::vec3 srgb);
// The inverse: sRGB-encoded components of an HSV colour (hexcone), for reference colours
// turned back into pixels (markers, test imagery).
glm::vec3 srgbFromHsv(glm::vec3 hsv);
// HSV of linear components: hsvFromSrgb of their sRGB encoding.
glm::vec3 hsvFromLinear(glm::vec3 linear);
// HSV of an 8-bit sRGB pixel.
glm::vec3 hsvFromSrgb8(uint8_t r, uint8_t g, uint8_t b);

// Hue difference on the colour circle: min(|a − b|, 1 − |a − b|), for a, b in [0, 1]; in [0, 0.5].
float hueDistance(float a, float b);
// ‖(Δh, Δs, Δv) ⊙ weights‖ with the wrapped hue difference (not clamped).
float weightedHsvDistance(glm::vec3 hsvA, glm::vec3 hsvB, glm::vec3 weights);
// The same with the NDVI and ExG terms where present: ‖(Δh, Δs, Δv, Δn, Δe) ⊙ (w, w_n, w_e)‖.
float weightedDistance(const ColourScoreParams& params, glm::vec3 hsv, float ndvi, float exg = kNoExg);

// ln s_i = −p · ln max(distance, kMinColourDistance): finite for every input.
float logColourScore(const ColourScoreParams& params, glm::vec3 hsv, float ndvi = kNoNdvi, float exg = kNoExg);
// s_i of eq. 16 (may be +inf in float only for extreme p; use logColourScore to compare).
float colourScore(const ColourScoreParams& params, glm::vec3 hsv, float ndvi = kNoNdvi);

// s_i / Σ s over `types` for base colour `hsv` into `out` (same size as `types`; sums to 1).
// Empty `types`: nothing to write.
void blendWeights(std::span<const ColourScoreParams> types, glm::vec3 hsv, std::span<float> out,
                  float ndvi = kNoNdvi);
std::vector<float> blendWeights(std::span<const ColourScoreParams> types, glm::vec3 hsv, float ndvi = kNoNdvi);

// Index of the highest score (the first of equals); `types` must not be empty.
size_t bestMatch(std::span<const ColourScoreParams> types, glm::vec3 hsv, float ndvi = kNoNdvi);

}  // namespace vegstream::vegetation
