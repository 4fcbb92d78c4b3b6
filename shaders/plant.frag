#version 450
#extension GL_GOOGLE_include_directive : require
// Plant shading, core seed 001_3eca9f2c7752e4fb.txt §2.4: eq. 14's ambient + Lambert + Phong
// specular plus eq. 13's translucency I_t = I_i k_t max(−n·ω, 0) exp(α / (n·ω)) for light from
// behind the blade; coefficients from the imagery colour under the plant (the same albedo the
// terrain pass gives that ground, so plants fade into the textured far terrain), darkened towards
// the ground by the neighbours' occlusion (Reeves and Blau 1985; seed 004 §2.3's
// height-dependent light). Coverage: the blade's alpha mask becomes the fragment's MSAA sample
// mask (alpha-to-coverage, computed here: round(alpha · samples) samples, rotated and dithered
// per pixel so neighbours do not repeat one pattern; without MSAA it is an alpha test with the
// same dither); shadows are black at 35 % coverage — a screen door, no sorting. The fixed-function
// alphaToCoverageEnable is not used: lavapipe (Mesa 22.3) resolves such fragments to wrong,
// whitish colours, and a computed mask is the same on every device.
#include "frame_uniforms.glsl"
#include "atmosphere.glsl"
#include "philox.glsl"
#include "seeding.glsl"
#include "classify_layout.glsl"
#include "plant_common.glsl"

layout(location = 0) in vec3 gPos;
layout(location = 1) in vec3 gNormal;
layout(location = 2) in vec2 gBlade;
layout(location = 3) flat in vec3 gGround;
layout(location = 4) flat in vec4 gPlant;  // colour modulation, s′, kind (0 blade, 1 stone, 2 head), shadow
layout(location = 5) flat in vec3 gUp;     // the ground's normal under the plant
layout(location = 0) out vec4 outColor;

const float kImageryExposure = 1.6;  // as shaders/terrain.frag: imagery is albedo × its day's light
const float kShadowAlpha = 0.35;
const float kAttenuation = 0.6;      // α of eq. 13: light absorbed crossing a blade of unit width

// The 4 × 4 Bayer threshold of this pixel, in (0, 1): the coverage dither.
float ditherThreshold() {
  const float bayer[16] = float[16](0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5);
  ivec2 p = ivec2(gl_FragCoord.xy) & 3;
  return (bayer[p.y * 4 + p.x] + 0.5) / 16.0;
}

void main() {
  bool shadow = gPlant.w > 0.5;
  float kind = gPlant.z;
  float alpha = 1.0;
  if (shadow)
    alpha = kShadowAlpha;
  else if (kind < 0.5)
    alpha = 1.0 - smoothstep(0.6, 1.0, abs(gBlade.x));
  else if (kind > 1.5)
    alpha = 1.0 - smoothstep(0.75, 1.0, length(vec2(gBlade.x, 2.0 * gBlade.y - 1.0)));
  // Alpha to coverage: k of the n samples, k = ⌊alpha · n + dither⌋, starting at a per-pixel sample.
  uint samples = max((pc.flags >> 8) & 0xffu, 1u);
  float d = ditherThreshold();
  uint k = min(uint(alpha * float(samples) + d), samples);
  if (k == 0u) discard;
  uint first = uint(d * 16.0) % samples;
  uint bits = (k >= 32u ? 0xffffffffu : (1u << k) - 1u);
  uint mask = ((bits << first) | (bits >> (samples - first))) & ((samples >= 32u ? 0xffffffffu : (1u << samples) - 1u));
  gl_SampleMask[0] = int(mask);
  alpha = 1.0;
  if (shadow) {
    outColor = vec4(0.0, 0.0, 0.0, alpha);
    return;
  }
  vec3 n = normalize(gNormal);
  vec3 v = normalize(-gPos);
  if (dot(n, v) < 0.0) n = -n;  // blades are two-sided: shade the face we see
  // A canopy of thin blades, or a bed of stones, is lit much like the ground it covers (a slope
  // turned from the sun stays dark): bend the normal towards the ground's.
  vec3 nLight = normalize(mix(n, gUp, 0.7));
  vec3 l = frame.sunDirection.xyz;
  float ndl = dot(nLight, l);
  vec3 albedo = gGround * kImageryExposure * 0.5 * gPlant.x;
  if (kind > 1.5) albedo = mix(albedo, vec3(0.55, 0.45, 0.12), 0.6) * 1.6;  // flower heads: yellow
  // Occlusion by the neighbours: dark at the root, the sunlit top of the canopy a little brighter
  // than the bare ground (stones: none).
  float occlusion = kind > 0.5 ? 1.0 : mix(0.45, 1.1, gBlade.y);
  vec3 kd = albedo * occlusion;
  vec3 ka = kd;
  vec3 kt = albedo * vec3(0.9, 1.0, 0.55) * occlusion;  // light through a leaf turns yellow-green
  float ks = (kind < 0.5 ? 0.015 : 0.01) * occlusion;
  vec3 ia = mix(frame.skyHorizon.rgb, frame.skyZenith.rgb, 0.5) * 0.35;
  vec3 ii = frame.sunColor.rgb;
  vec3 r = reflect(-l, nLight);
  vec3 lit = ia * ka + ii * (kd * max(ndl, 0.0) + ks * pow(max(dot(v, r), 0.0), 32.0));
  float ndlFace = dot(n, l);  // translucency goes through the blade's own face
  if (ndlFace < 0.0 && kind < 0.5) lit += ii * kt * (-ndlFace) * exp(kAttenuation / ndlFace);  // eq. 13
  outColor = vec4(applyAerialPerspective(lit, gPos), alpha);
}
