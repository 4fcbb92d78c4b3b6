// The atmosphere's ray marches (Hillaire 2020 §5): in-scattered luminance and transmittance along
// a view ray, and the multiple-scattering transfer Ψ_ms of §5.5. Shared like atmosphere_model.glsl
// (needs it). The includer provides the two lookups the marches read, so the GPU reads its LUTs
// and the CPU reference integrates them by brute force:
//   vec3 sunTransmittance(float r, float muS)   transmittance to the sun (0 in the earth's shadow)
//   vec3 multiScattering(float r, float muS)    Ψ_ms per unit of sun illuminance
//
// A ray starts at radius r with cosine mu to the up, cosine nu to the sun, the sun at cosine muS
// to the up; nu is constant along a straight ray. Each step integrates the in-scattering
// S·(1 − e^(−σ_t Δt))/σ_t over its length (Hillaire's energy-conserving form, §5.3).

struct AtmosphereRay {
  float r;
  float mu;
  float muS;
  float nu;
};

// Adds the in-scattering over [t0, t1] (midpoint rule, `steps` steps) to `luminance`, scaled by
// the running `transmittance`, which it advances. `multiple`: with Hillaire's Ψ_ms term.
VS_INLINE void marchSegment(AtmosphereRay ray, float t0, float t1, int steps, bool multiple,
                            VS_INOUT(vec3) luminance, VS_INOUT(vec3) transmittance) {
  float dt = (t1 - t0) / float(steps);
  float phaseR = rayleighPhase(ray.nu), phaseM = miePhase(ray.nu);
  for (int i = 0; i < steps; ++i) {
    float t = t0 + (float(i) + 0.5f) * dt;
    float ri = radiusAlong(ray.r, ray.mu, t);
    float muSi = sunCosineAlong(ray.r, ray.mu, ray.muS, ray.nu, t);
    float h = ri - kBottomRadiusKm;
    vec3 sigmaR = rayleighScatteringAt(h);
    float sigmaM = mieScatteringAt(h);
    vec3 ext = extinctionAt(h);
    vec3 scatter = (sigmaR * phaseR + vec3(sigmaM * phaseM)) * sunTransmittance(ri, muSi);
    if (multiple) scatter = scatter + (sigmaR + vec3(sigmaM)) * multiScattering(ri, muSi);
    vec3 stepT = exp(-ext * dt);
    luminance = luminance + transmittance * (scatter * kSunIlluminance) * (vec3(1.0f) - stepT) / ext;
    transmittance = transmittance * stepT;
  }
}

// The luminance of the sky along a whole ray, to the ground or the top (the sky-view LUT).
VS_INLINE vec3 skyLuminanceMarched(AtmosphereRay ray, int steps, bool multiple) {
  vec3 luminance = vec3(0.0f);
  vec3 transmittance = vec3(1.0f);
  marchSegment(ray, 0.0f, distanceToEnd(ray.r, ray.mu), steps, multiple, luminance, transmittance);
  return luminance;
}

// Hillaire 2020 §5.5, per unit sun illuminance: over `n` × 2n directions of the sphere, the
// second-order luminance L_2 (sun light scattered once with an isotropic phase, plus the lit
// ground at the ray's end) and the transfer f_ms, each averaged over the sphere (the isotropic
// phase 1/4π times the sphere's 4π); Ψ_ms = L_2 / (1 − f_ms).
VS_INLINE vec3 multiScatteringTransfer(float r, float muS, int n, int steps) {
  vec3 l2 = vec3(0.0f);
  vec3 fms = vec3(0.0f);
  float isotropic = 1.0f / (4.0f * kAtmospherePi);
  float sinS = sqrt(max(1.0f - muS * muS, 0.0f));
  for (int i = 0; i < n; ++i) {
    float mu = 1.0f - 2.0f * (float(i) + 0.5f) / float(n);  // equal-area bands
    float sinV = sqrt(max(1.0f - mu * mu, 0.0f));
    for (int j = 0; j < 2 * n; ++j) {
      float phi = 2.0f * kAtmospherePi * (float(j) + 0.5f) / float(2 * n);
      float nu = sinV * cos(phi) * sinS + mu * muS;
      float tEnd = distanceToEnd(r, mu);
      float dt = tEnd / float(steps);
      vec3 lum = vec3(0.0f), f = vec3(0.0f), trans = vec3(1.0f);
      for (int k = 0; k < steps; ++k) {
        float t = (float(k) + 0.5f) * dt;
        float ri = radiusAlong(r, mu, t);
        float h = ri - kBottomRadiusKm;
        vec3 sigmaS = rayleighScatteringAt(h) + vec3(mieScatteringAt(h));
        vec3 ext = extinctionAt(h);
        vec3 stepT = exp(-ext * dt);
        vec3 integral = (vec3(1.0f) - stepT) / ext;
        lum = lum + trans * sigmaS * sunTransmittance(ri, (r * muS + t * nu) / ri) * isotropic * integral;
        f = f + trans * sigmaS * integral;
        trans = trans * stepT;
      }
      if (rayHitsGround(r, mu)) {  // the ground at the ray's end, lit by the sun
        float rg = radiusAlong(r, mu, tEnd);
        float muSg = (r * muS + tEnd * nu) / rg;
        lum = lum + trans * sunTransmittance(rg, muSg) * max(muSg, 0.0f) * kGroundAlbedo / kAtmospherePi;
      }
      l2 = l2 + lum;
      fms = fms + f * isotropic;
    }
  }
  float count = float(2 * n * n);
  l2 = l2 / count;
  fms = fms * (4.0f * kAtmospherePi) / count;
  return l2 / (vec3(1.0f) - fms);
}
