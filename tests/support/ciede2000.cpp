// sRGB → CIELAB and CIEDE2000 (ciede2000.h). The ΔE00 steps follow Sharma, Wu & Dalal 2005,
// equations (1)–(22), numbered in the comments as in the paper.

#include "tests/support/ciede2000.h"

#include <cmath>

namespace vegstream::testing {
namespace {

constexpr double kPi = 3.14159265358979323846;
double deg(double rad) { return rad * 180.0 / kPi; }
double rad(double deg) { return deg * kPi / 180.0; }

// CIE 15 f(t) of the L*a*b* definition.
double labF(double t) {
  constexpr double d = 6.0 / 29.0;
  return t > d * d * d ? std::cbrt(t) : t / (3.0 * d * d) + 4.0 / 29.0;
}

// Hue angle in degrees 0 … 360 of (a', b); 0 when both are 0 (eq. 4).
double hueDeg(double ap, double b) {
  if (ap == 0.0 && b == 0.0) return 0.0;
  const double h = deg(std::atan2(b, ap));
  return h < 0.0 ? h + 360.0 : h;
}

}  // namespace

double srgbToLinear(double e) { return e <= 0.04045 ? e / 12.92 : std::pow((e + 0.055) / 1.055, 2.4); }
double linearToSrgb(double l) { return l <= 0.0031308 ? 12.92 * l : 1.055 * std::pow(l, 1.0 / 2.4) - 0.055; }

Lab labFromLinear(double r, double g, double b) {
  // IEC 61966-2-1 linear RGB → XYZ (D65), then CIELAB with the D65 white (0.9505, 1, 1.089).
  const double x = 0.4124 * r + 0.3576 * g + 0.1805 * b;
  const double y = 0.2126 * r + 0.7152 * g + 0.0722 * b;
  const double z = 0.0193 * r + 0.1192 * g + 0.9505 * b;
  const double fx = labF(x / 0.9505), fy = labF(y / 1.0), fz = labF(z / 1.0890);
  return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

Lab labFromLinear(glm::vec3 c) { return labFromLinear(c.r, c.g, c.b); }

Lab labFromSrgb8(uint8_t r, uint8_t g, uint8_t b) {
  return labFromLinear(srgbToLinear(r / 255.0), srgbToLinear(g / 255.0), srgbToLinear(b / 255.0));
}

double ciede2000(const Lab& x, const Lab& y) {
  // (2)–(3): chroma, the a* axis scaled by G, C' and h'.
  const double c1 = std::hypot(x.a, x.b), c2 = std::hypot(y.a, y.b);
  const double cMean7 = std::pow((c1 + c2) / 2.0, 7.0);
  const double g = 0.5 * (1.0 - std::sqrt(cMean7 / (cMean7 + std::pow(25.0, 7.0))));
  const double a1 = (1.0 + g) * x.a, a2 = (1.0 + g) * y.a;
  const double cp1 = std::hypot(a1, x.b), cp2 = std::hypot(a2, y.b);
  const double h1 = hueDeg(a1, x.b), h2 = hueDeg(a2, y.b);
  // (8)–(10): ΔL', ΔC', Δh' (0 when either chroma is 0), ΔH'.
  const double dL = y.L - x.L, dC = cp2 - cp1;
  double dh = 0.0;
  if (cp1 * cp2 != 0.0) {
    dh = h2 - h1;
    if (dh > 180.0)
      dh -= 360.0;
    else if (dh < -180.0)
      dh += 360.0;
  }
  const double dH = 2.0 * std::sqrt(cp1 * cp2) * std::sin(rad(dh / 2.0));
  // (12)–(14): means; the mean hue across the 0/360 wrap.
  const double lMean = (x.L + y.L) / 2.0, cpMean = (cp1 + cp2) / 2.0;
  double hMean = h1 + h2;
  if (cp1 * cp2 != 0.0) {
    if (std::abs(h1 - h2) <= 180.0)
      hMean /= 2.0;
    else if (h1 + h2 < 360.0)
      hMean = (h1 + h2 + 360.0) / 2.0;
    else
      hMean = (h1 + h2 - 360.0) / 2.0;
  }
  // (15)–(21): weights and the rotation term.
  const double t = 1.0 - 0.17 * std::cos(rad(hMean - 30.0)) + 0.24 * std::cos(rad(2.0 * hMean)) +
                   0.32 * std::cos(rad(3.0 * hMean + 6.0)) - 0.20 * std::cos(rad(4.0 * hMean - 63.0));
  const double dTheta = 30.0 * std::exp(-std::pow((hMean - 275.0) / 25.0, 2.0));
  const double cpMean7 = std::pow(cpMean, 7.0);
  const double rc = 2.0 * std::sqrt(cpMean7 / (cpMean7 + std::pow(25.0, 7.0)));
  const double l50 = (lMean - 50.0) * (lMean - 50.0);
  const double sl = 1.0 + 0.015 * l50 / std::sqrt(20.0 + l50);
  const double sc = 1.0 + 0.045 * cpMean;
  const double sh = 1.0 + 0.015 * cpMean * t;
  const double rt = -std::sin(rad(2.0 * dTheta)) * rc;
  // (22).
  const double l = dL / sl, c = dC / sc, h = dH / sh;
  return std::sqrt(l * l + c * c + h * h + rt * c * h);
}

}  // namespace vegstream::testing
