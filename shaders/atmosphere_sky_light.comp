#version 450
// The frame's light (render/atmosphere_pass.h): the sun's illuminance at the camera (through the
// transmittance LUT) and the sky's irradiance on an upward, a vertical and a downward surface,
// integrated over the sky-view LUT (16 zenith bands × 32 azimuths). One workgroup; the sums run
// in a fixed order (deterministic).
#extension GL_GOOGLE_include_directive : require
#include "common/atmosphere_lut_io.glsl"
layout(local_size_x = 32) in;
shared vec3 upSum[32], sideSum[32];

void main() {
  uint a = gl_LocalInvocationIndex;  // this invocation's azimuth column
  float r = pc.view.x;
  float azimuth = (float(a) + 0.5) / 32.0 * 2.0 * kAtmospherePi - kAtmospherePi;  // −π … π from the sun
  vec3 up = vec3(0.0), side = vec3(0.0);
  const int bands = 16;
  float dPhi = 2.0 * kAtmospherePi / 32.0;
  for (int b = 0; b < bands; ++b) {  // the upper hemisphere, uniform in zenith angle
    float zenith = (float(b) + 0.5) / float(bands) * 0.5 * kAtmospherePi;
    float dTheta = 0.5 * kAtmospherePi / float(bands);
    vec2 uv = skyViewUvFromDirection(r, cos(zenith), abs(azimuth));
    vec3 l = textureLod(skyViewLut, lutTexelUv(uv, vec2(textureSize(skyViewLut, 0))), 0.0).rgb;
    float dOmega = sin(zenith) * dTheta * dPhi;
    up += l * cos(zenith) * dOmega;
    // A vertical surface facing azimuth 0 … (averaged over its azimuth): ∫ max(cos, 0) over the
    // azimuth gives sin θ / π of the full turn.
    side += l * sin(zenith) / kAtmospherePi * dOmega;
  }
  upSum[a] = up;
  sideSum[a] = side;
  barrier();
  if (a != 0u) return;
  vec3 u = vec3(0.0), s = vec3(0.0);
  for (int i = 0; i < 32; ++i) {
    u += upSum[i];
    s += sideSum[i];
  }
  vec3 sun = kSunIlluminance * sunTransmittance(r, pc.view.y);
  skyLightOut.sunIlluminance = vec4(sun, pc.view.y);
  skyLightOut.skyUp = vec4(u, 0.0);
  skyLightOut.skySide = vec4(s + 0.5 * kGroundAlbedo * (sun * max(pc.view.y, 0.0) + u), 0.0);
  skyLightOut.skyDown = vec4(kGroundAlbedo * (sun * max(pc.view.y, 0.0) + u), 0.0);
}
