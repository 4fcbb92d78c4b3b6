// The atmosphere (issue 39 item 2): Hillaire 2020, "A Scalable and Production Ready Sky and
// Atmosphere Rendering Technique" (EGSR), with Bruneton & Neyret 2008 ("Precomputed Atmospheric
// Scattering") and Bruneton 2017's reference implementation for the media and the transmittance
// LUT's parameterisation. GLSL for the LUT passes (shaders/atmosphere_*.comp), C++ for the CPU
// reference and its tests (render/atmosphere_model.h): the same source text, in the subset both
// read alike (simulation/shared/glsl_compat.h: f suffixes, no swizzles, VS_INLINE).
//
// Lengths in km, the planet a sphere of radius kBottomRadiusKm with the camera above its top
// (the dataset's heights MSL / 1000). Radiance in the scene's units (shaders/common/exposure.glsl:
// 1 = 1e4 cd/m²), the sun's illuminance outside the atmosphere kSunIlluminance = 12 (120 000 lux,
// white: the LUTs are spectral only through the three channels' coefficients).
//
// Media (Hillaire 2020 §4 / Bruneton 2017's Earth): Rayleigh scattering σ_R(h) = β_R e^(−h/8),
// Mie scattering and extinction e^(−h/1.2) (absorption = extinction − scattering), ozone
// absorption in a tent of half-width 15 km around 25 km. Phase: Rayleigh 3/(16π)(1 + c²),
// Mie the Cornette–Shanks function with g = 0.8.

const float kBottomRadiusKm = 6360.0f;
const float kTopRadiusKm = 6460.0f;
const float kRayleighScaleKm = 8.0f;
const float kMieScaleKm = 1.2f;
const float kMieScatteringPerKm = 3.996e-3f;
const float kMieExtinctionPerKm = 4.440e-3f;
const float kMieG = 0.8f;
const float kOzoneCentreKm = 25.0f;
const float kOzoneHalfWidthKm = 15.0f;
const float kSunIlluminance = 12.0f;
const float kGroundAlbedo = 0.15f;  // the average ground the multiple scattering sees
const float kAtmospherePi = 3.14159265358979f;

VS_INLINE vec3 rayleighScatteringAt(float hKm) {
  return vec3(5.802e-3f, 13.558e-3f, 33.1e-3f) * exp(-max(hKm, 0.0f) / kRayleighScaleKm);
}
VS_INLINE float mieScatteringAt(float hKm) { return kMieScatteringPerKm * exp(-max(hKm, 0.0f) / kMieScaleKm); }

VS_INLINE vec3 extinctionAt(float hKm) {
  float h = max(hKm, 0.0f);
  float ozone = max(0.0f, 1.0f - abs(h - kOzoneCentreKm) / kOzoneHalfWidthKm);
  return rayleighScatteringAt(h) + vec3(kMieExtinctionPerKm * exp(-h / kMieScaleKm)) +
         vec3(0.650e-3f, 1.881e-3f, 0.085e-3f) * ozone;
}

VS_INLINE float rayleighPhase(float c) { return 3.0f / (16.0f * kAtmospherePi) * (1.0f + c * c); }
VS_INLINE float miePhase(float c) {
  float g = kMieG;
  float k = 3.0f / (8.0f * kAtmospherePi) * (1.0f - g * g) / (2.0f + g * g);
  return k * (1.0f + c * c) / pow(max(1.0f + g * g - 2.0f * g * c, 1e-4f), 1.5f);
}

// From radius r along a direction whose cosine with the local up is mu: the distance to the top
// of the atmosphere (from inside it) and to the ground (0 when the ray misses it).
VS_INLINE float distanceToTop(float r, float mu) {
  float disc = r * r * (mu * mu - 1.0f) + kTopRadiusKm * kTopRadiusKm;
  return max(-r * mu + sqrt(max(disc, 0.0f)), 0.0f);
}
VS_INLINE bool rayHitsGround(float r, float mu) {
  return mu < 0.0f && r * r * (mu * mu - 1.0f) + kBottomRadiusKm * kBottomRadiusKm >= 0.0f;
}
VS_INLINE float distanceToGround(float r, float mu) {
  float disc = r * r * (mu * mu - 1.0f) + kBottomRadiusKm * kBottomRadiusKm;
  return max(-r * mu - sqrt(max(disc, 0.0f)), 0.0f);
}
// Where the ray ends: the ground if it hits it, else the top.
VS_INLINE float distanceToEnd(float r, float mu) {
  return rayHitsGround(r, mu) ? distanceToGround(r, mu) : distanceToTop(r, mu);
}
// Radius and the sun's cosine with the local up after t km along a ray from radius r (cosine mu
// with the up, nu with the sun; muS: the sun's cosine with the up at the start).
VS_INLINE float radiusAlong(float r, float mu, float t) { return sqrt(max(t * t + 2.0f * r * mu * t + r * r, 0.0f)); }
VS_INLINE float sunCosineAlong(float r, float mu, float muS, float nu, float t) {
  return (r * muS + t * nu) / radiusAlong(r, mu, t);
}

// Transmittance from radius r to the top along cosine mu, by the midpoint rule (the LUT's texels
// and the reference's brute force).
VS_INLINE vec3 transmittanceToTopMarched(float r, float mu, int steps) {
  float d = distanceToTop(r, mu);
  float dt = d / float(steps);
  vec3 depth = vec3(0.0f);
  for (int i = 0; i < steps; ++i) {
    float t = (float(i) + 0.5f) * dt;
    depth = depth + extinctionAt(radiusAlong(r, mu, t) - kBottomRadiusKm) * dt;
  }
  return exp(-depth);
}

// The transmittance LUT's parameterisation (Bruneton 2017 §"Transmittance", precomputation):
// u from the distance to the top between its minimum and maximum at r, v from the distance to the
// horizon. Both 0 … 1, texel centres handled by the caller.
VS_INLINE vec2 transmittanceUvFromRMu(float r, float mu) {
  float H = sqrt(kTopRadiusKm * kTopRadiusKm - kBottomRadiusKm * kBottomRadiusKm);
  float rho = sqrt(max(r * r - kBottomRadiusKm * kBottomRadiusKm, 0.0f));
  float d = distanceToTop(r, mu);
  float dMin = kTopRadiusKm - r;
  float dMax = rho + H;
  return vec2((d - dMin) / max(dMax - dMin, 1e-6f), rho / H);
}
VS_INLINE vec2 transmittanceRMuFromUv(vec2 uv) {
  float H = sqrt(kTopRadiusKm * kTopRadiusKm - kBottomRadiusKm * kBottomRadiusKm);
  float rho = H * uv.y;
  float r = sqrt(rho * rho + kBottomRadiusKm * kBottomRadiusKm);
  float dMin = kTopRadiusKm - r;
  float dMax = rho + H;
  float d = dMin + uv.x * (dMax - dMin);
  float mu = d == 0.0f ? 1.0f : (H * H - rho * rho - d * d) / (2.0f * r * d);
  return vec2(r, clamp(mu, -1.0f, 1.0f));
}

// The multiple-scattering LUT's parameterisation (Hillaire 2020 §5.5): u the sun's cosine with
// the up (−1 … 1), v the altitude (0 … top).
VS_INLINE vec2 multiScatteringUvFromRMuS(float r, float muS) {
  return vec2(clamp(0.5f + 0.5f * muS, 0.0f, 1.0f),
              clamp((r - kBottomRadiusKm) / (kTopRadiusKm - kBottomRadiusKm), 0.0f, 1.0f));
}
VS_INLINE vec2 multiScatteringRMuSFromUv(vec2 uv) {
  return vec2(kBottomRadiusKm + uv.y * (kTopRadiusKm - kBottomRadiusKm), uv.x * 2.0f - 1.0f);
}

// The sky-view LUT's parameterisation (Hillaire 2020 §5.3): v the view's zenith angle, squeezed
// towards the horizon (half the texels above it, half below), u the azimuth from the sun's,
// 0 … π, square-rooted towards the sun. Returns (cos zenith, azimuth).
VS_INLINE vec2 skyViewDirectionFromUv(float r, vec2 uv) {
  float vHorizon = sqrt(max(r * r - kBottomRadiusKm * kBottomRadiusKm, 0.0f));
  float beta = acos(clamp(vHorizon / r, -1.0f, 1.0f));  // the horizon's angle below the level
  float zenithHorizon = kAtmospherePi * 0.5f + beta;
  float zenith;
  if (uv.y < 0.5f) {
    float c = 1.0f - 2.0f * uv.y;
    zenith = zenithHorizon * (1.0f - c * c);
  } else {
    float c = uv.y * 2.0f - 1.0f;
    zenith = zenithHorizon + (kAtmospherePi - zenithHorizon) * c * c;
  }
  return vec2(cos(zenith), uv.x * uv.x * kAtmospherePi);
}
VS_INLINE vec2 skyViewUvFromDirection(float r, float cosZenith, float azimuth) {
  float vHorizon = sqrt(max(r * r - kBottomRadiusKm * kBottomRadiusKm, 0.0f));
  float beta = acos(clamp(vHorizon / r, -1.0f, 1.0f));
  float zenithHorizon = kAtmospherePi * 0.5f + beta;
  float zenith = acos(clamp(cosZenith, -1.0f, 1.0f));
  float v;
  if (zenith < zenithHorizon) {
    v = 0.5f * (1.0f - sqrt(max(1.0f - zenith / zenithHorizon, 0.0f)));
  } else {
    v = 0.5f + 0.5f * sqrt(max((zenith - zenithHorizon) / (kAtmospherePi - zenithHorizon), 0.0f));
  }
  return vec2(sqrt(clamp(abs(azimuth) / kAtmospherePi, 0.0f, 1.0f)), v);
}
