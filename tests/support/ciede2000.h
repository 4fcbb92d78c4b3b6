#pragma once
// Colour difference for tests that compare colours as people see them: CIELAB (D65) from sRGB
// and CIEDE2000 (ΔE00) between two CIELAB colours.
//
// sRGB: IEC 61966-2-1:1999 (the piecewise transfer curve, the Rec. 709 primaries, D65 white).
// CIELAB: CIE 15:2004 with the D65 reference white of the sRGB standard (Y = 1).
// ΔE00: CIE 142-2001 as written out by G. Sharma, W. Wu, E. N. Dalal, "The CIEDE2000
// colour-difference formula: implementation notes, supplementary test data, and mathematical
// observations", Color Research & Application 30(1), 21–30, 2005 (kL = kC = kH = 1), checked
// against their published test pairs (ciede2000_test.cpp).

#include <cstdint>

#include <glm/vec3.hpp>

namespace vegstream::testing {

struct Lab {
  double L = 0.0;  // 0 … 100
  double a = 0.0;
  double b = 0.0;
};

// ΔE00 between two colours; symmetric, 0 for equal colours.
double ciede2000(const Lab& x, const Lab& y);

// CIELAB of linear-light sRGB (Rec. 709 primaries, D65), components 0 … 1 (larger ones allowed).
Lab labFromLinear(glm::vec3 linear);
Lab labFromLinear(double r, double g, double b);

// CIELAB of an 8-bit sRGB-encoded colour (decoded with the sRGB curve first).
Lab labFromSrgb8(uint8_t r, uint8_t g, uint8_t b);

// The sRGB transfer curve (IEC 61966-2-1): encoded 0 … 1 ↔ linear 0 … 1.
double srgbToLinear(double encoded);
double linearToSrgb(double linear);

}  // namespace vegstream::testing
