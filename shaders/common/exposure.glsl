// Exposure and tone mapping (issue 39 item 3), shared by exposure_histogram.comp,
// exposure_resolve.comp and tonemap.comp; render/tonemap_pass.h mirrors the layout and the
// constants (static_assert there).
//
// Units. The scene is rendered in linear HDR where one unit of radiance is kLuminanceUnitCdM2
// cd/m² (an RGB triple read as luminous: the sun's illuminance outside the atmosphere is
// atmosphere.glsl's kSunIlluminance units, 120 000 lux). Exposure is an EV100 (ISO 100 speed,
// the camera's saturation-based calibration K = 12.5 · 100 / 1.2 … ≈ Lagarde & de Rousiers,
// "Moving Frostbite to PBR", 2014, §4.3): the tone curve's input is
//   x = radiance · kLuminanceUnitCdM2 / (1.2 · 2^EV100).
//
// Automatic exposure: a histogram of log2 luminance (kExposureBins bins over
// [kLogLumMin, kLogLumMax], in units), the mean log luminance of the pixels between the
// kExposureLow-th and kExposureHigh-th fractions (the darkest shadows and the sun and its glare
// do not move it), and the EV100 that puts that mean at kExposureKey (middle grey). For stills
// and recordings it is a function of the frame alone (integer histogram counts, a sequential
// sum: the same frame gives the same bytes); the window smooths it over time.

const int kExposureBins = 64;
const float kLogLumMin = -16.0;  // units: 1.5e-5 · 1e4 cd/m² ≈ 0.15 cd/m² (deep dusk)
const float kLogLumMax = 4.0;    // 16 units = 1.6e5 cd/m² (beyond: the sun's disc)
const float kLuminanceUnitCdM2 = 1.0e4;
const float kExposureLow = 0.40, kExposureHigh = 0.95;
const float kExposureKey = 0.18;
const float kAdaptPerS = 1.5;  // window: the exposure moves 1 − e^(−1.5 t) of the way in t seconds

const uint kToneAuto = 0u, kToneFixed = 1u, kToneIdentity = 2u;

struct ExposureState {
  uint bins[kExposureBins];
  float ev;      // the last frame's EV100 (the window adapts from it)
  uint valid;    // 1 once a frame has written ev
  uint pad0, pad1;
};

// The tone curve's input scale for an EV100.
float exposureScale(float ev100) { return kLuminanceUnitCdM2 / (1.2 * exp2(ev100)); }
// The EV100 that maps a log2 luminance (units) to the key.
float evForLogLuminance(float logLum) { return log2(kLuminanceUnitCdM2 * exp2(logLum) / (1.2 * kExposureKey)); }

float luminanceOf(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

// AgX (Troy Sobotka's "AgX" view transform, as shipped in Blender 4): a log2 encoding of the
// inset primaries over [−12.47, 4.03] stops around 0.18, a sigmoid (here the 6th-order polynomial
// fit of its default contrast curve), the outset matrix, and the 2.2 display power. Input: linear
// Rec. 709 scene values after exposure; output: linear display values 0 … 1.
vec3 agxToneMap(vec3 c) {
  const mat3 inset = mat3(0.842479062253094, 0.0423282422610123, 0.0423756549057051,
                          0.0784335999999992, 0.878468636469772, 0.0784336,
                          0.0792237451477643, 0.0791661274605434, 0.879142973793104);
  const mat3 outset = mat3(1.19687900512017, -0.0528968517574562, -0.0529716355144438,
                           -0.0980208811401368, 1.15190312990417, -0.0980434501171241,
                           -0.0990297440797205, -0.0989611768448433, 1.15107367264116);
  const float minEv = -12.47393, maxEv = 4.026069;
  vec3 v = inset * max(c, vec3(0.0));
  v = clamp(log2(max(v, vec3(1e-10))), minEv, maxEv);
  v = (v - minEv) / (maxEv - minEv);
  vec3 v2 = v * v, v4 = v2 * v2;
  v = 15.5 * v4 * v2 - 40.14 * v4 * v + 31.96 * v4 - 6.868 * v2 * v + 0.4298 * v2 + 0.1191 * v - 0.00232;
  v = outset * v;
  return pow(clamp(v, 0.0, 1.0), vec3(2.2));
}

// IEC 61966-2-1 sRGB encoding of a linear value 0 … 1.
vec3 srgbEncoded(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}
