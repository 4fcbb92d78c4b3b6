#pragma once
// The colour the species choice sees (issue 41 item 1): the imagery's linear colour through the
// dataset's colour calibration (estimated at import, datasets/colour_calibration.h: robust
// levels, chroma and exposure normalisation onto the reference scene the catalog was written
// on), then HSV of its sRGB encoding (colour_score.h's convention) and the excess-green index
//
//     ExG = (2 G − R − B) / (R + G + B)      (Woebbecke et al. 1995, on chromaticities r, g, b:
//                                             ExG = 2g − r − b), of the calibrated linear colour,
//
// in −1 … 2: about 0 for greys whatever their brightness, > 0.15 for green leaves, < 0 for red
// rock and sand. On calibrated chromaticities it is stable under colour casts, and it stands in
// for the NDVI where the dataset has no near-infrared band (colour_score.h, catalog key "exg").
// A black pixel (R + G + B < 1e-4) has ExG 0.
//
// One affine map in linear light, c = clamp(M x + o, 0, 1) with M row by row written out as
// m0 x + m1 y + m2 z + o (no dot(), so the GLSL twin shaders/common/colour_calibration.glsl
// computes the same floats operation for operation; tests/render/colour_score_gpu_test.cpp
// compares them). The identity (M = I, o = 0: datasets without a calibration) gives exactly
// hsvFromLinear(x), the HSV the choice saw before calibrations existed.
//
// The rendered terrain does not see the calibration: only the species choice (plants, trees,
// `query`, `plants`) does.

#include <array>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace vegstream::vegetation {

struct ColourCalibration {
  // Rows of the affine map: xyz the row of M, w its offset.
  std::array<glm::vec4, 3> rows{glm::vec4(1, 0, 0, 0), glm::vec4(0, 1, 0, 0), glm::vec4(0, 0, 1, 0)};
  bool isIdentity() const;
};

// What the colour score reads of one ground colour.
struct GroundColour {
  glm::vec3 hsv{0.0f};  // of the calibrated colour (sRGB-encoded HSV, colour_score.h)
  float exg = 0.0f;     // ExG of the calibrated linear colour, −1 … 2
};

inline constexpr float kMinChromaticitySum = 1e-4f;

// The calibrated linear colour, clamped to 0 … 1.
glm::vec3 calibrateLinear(const ColourCalibration& c, glm::vec3 linear);
// ExG of a linear colour (0 for black).
float excessGreen(glm::vec3 linear);
// Both, of the imagery's linear colour.
GroundColour calibratedGround(const ColourCalibration& c, glm::vec3 linear);

}  // namespace vegstream::vegetation
