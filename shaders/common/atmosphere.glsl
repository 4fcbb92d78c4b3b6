// Sky colour and aerial perspective, shared by the sky pass and every surface pass so distant
// terrain fades into exactly the sky behind it. Needs frame_uniforms.glsl.

vec3 skyColor(vec3 dir) {
  float up = clamp(dir.z, 0.0, 1.0);
  vec3 sky = mix(frame.skyHorizon.rgb, frame.skyZenith.rgb, pow(up, 0.45));
  // Below the horizon: the haze colour, slightly darker, so the far ground line is soft.
  if (dir.z < 0.0) sky = frame.skyHorizon.rgb * mix(1.0, 0.8, clamp(-dir.z * 4.0, 0.0, 1.0));
  float sunCos = max(dot(dir, frame.sunDirection.xyz), 0.0);
  sky += frame.sunColor.rgb * (0.25 * pow(sunCos, 8.0) + 8.0 * pow(sunCos, 2000.0));
  return sky;
}

// Exponential height fog integrated along the ray from the camera to a point at `offset`
// (camera-relative, metres): optical depth = density · ∫ exp(−falloff · height) ds.
float fogTransmittance(vec3 offset) {
  float dist = length(offset);
  float h0 = frame.fog.z;
  float falloff = frame.fog.y;
  float dh = offset.z * falloff;
  float integral = abs(dh) > 1e-4 ? (1.0 - exp(-dh)) / dh : 1.0;
  float opticalDepth = frame.fog.x * exp(-falloff * h0) * dist * integral;
  return exp(-opticalDepth);
}

vec3 applyAerialPerspective(vec3 color, vec3 offset) {
  vec3 dir = normalize(offset);
  return mix(skyColor(dir), color, fogTransmittance(offset));
}
#include "sun_shadow.glsl"
