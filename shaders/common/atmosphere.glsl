// The sky, the light and the aerial perspective every pass shares (issue 39 item 2), read from the
// frame's atmosphere LUTs (render/atmosphere_pass.h; Hillaire 2020): the sky-view LUT for the sky,
// the aerial-perspective volume for anything at a distance, and the frame's sun illuminance and
// sky irradiance, so the terrain, the plants and the trees are lit by one light and fade into
// exactly the sky behind them. Radiance in the scene's units (exposure.glsl). Needs
// frame_uniforms.glsl (frame.atmosphere: x the camera's radius in km, y the aerial volume's far
// distance in km).
#include "simulation/shared/shared_code_macros.glsl"
#include "atmosphere_model.glsl"

layout(set = 0, binding = 7) uniform sampler2D skyViewLut;
layout(set = 0, binding = 8) uniform sampler3D aerialLut;
layout(set = 0, binding = 9, std430) readonly buffer SkyLight {
  vec4 sunIlluminance;  // rgb at the camera; w: the sun's cosine with the up
  vec4 skyUp, skySide, skyDown;
} skyLight;

const float kSunAngularRadius = 0.004654;  // rad: 0.2667°

// The azimuth of a direction from the sun's, 0 … π.
float azimuthFromSun(vec3 dir) {
  vec2 d = dir.xy, s = frame.sunDirection.xy;
  float ld = length(d), ls = length(s);
  if (ld < 1e-6 || ls < 1e-6) return 0.0;
  return acos(clamp(dot(d, s) / (ld * ls), -1.0, 1.0));
}

vec2 atmosphereLutUv(vec2 uv, vec2 size) { return (uv * (size - 1.0) + 0.5) / size; }

// The sky's radiance towards `dir` (unit, local ENU), the sun's disc included.
vec3 skyColor(vec3 dir) {
  vec2 uv = skyViewUvFromDirection(frame.atmosphere.x, dir.z, azimuthFromSun(dir));
  vec3 sky = textureLod(skyViewLut, atmosphereLutUv(uv, vec2(textureSize(skyViewLut, 0))), 0.0).rgb;
  float c = dot(dir, frame.sunDirection.xyz);
  float discCos = cos(kSunAngularRadius);
  if (c > discCos) {  // the disc: its illuminance over its solid angle, limb-darkened
    float x = clamp((1.0 - c) / (1.0 - discCos), 0.0, 1.0);
    float limb = 1.0 - 0.6 * (1.0 - sqrt(1.0 - x));
    sky += skyLight.sunIlluminance.rgb / (kAtmospherePi * kSunAngularRadius * kSunAngularRadius) * limb;
  }
  return min(sky, vec3(60000.0));  // half floats
}

// The sky's colour dithered for the packed-float colour target (render/render_targets.h: 6, 6
// and 5 bits of mantissa): scaled by 1 + (u − ½)·2^−m per channel, u a hash of the pixel in
// [0, 1), so the gradient's steps (3 % for the blue) become a fine, fixed noise instead of bands.
// Deterministic: the same pixel always gets the same u.
vec3 ditheredSky(vec3 sky, uvec2 px) {
  uint h = px.x * 0x8da6b343u ^ px.y * 0xd8163841u;
  h = (h ^ (h >> 15)) * 0x2c1b3c6du;
  h ^= h >> 12;
  float u = float(h & 0xffffu) / 65536.0;
  return sky * (vec3(1.0) + (u - 0.5) * vec3(1.0 / 64.0, 1.0 / 64.0, 1.0 / 32.0));
}

// The air between the camera and a point at `offset` (camera-relative, m): xyz the light it
// scatters towards the camera, w its transmittance (the point is seen as colour · w + xyz).
vec4 aerialPerspective(vec3 offset) {
  float d = length(offset);
  if (d < 1e-3) return vec4(0.0, 0.0, 0.0, 1.0);
  vec3 dir = offset / d;
  vec2 uv = skyViewUvFromDirection(frame.atmosphere.x, dir.z, azimuthFromSun(dir));
  float w = sqrt(clamp(d * 1e-3 / frame.atmosphere.y, 0.0, 1.0));  // slices: far · ((k + 1) / n)²
  ivec3 size = textureSize(aerialLut, 0);
  // Slice k holds the distance ((k + 1) / n)²: w = (k + 1) / n ↔ coordinate (k + 0.5) / n; nearer
  // than the first slice, the first slice's values scaled down with the distance.
  float slice = w * float(size.z) - 1.0;
  vec3 coord = vec3(atmosphereLutUv(uv, vec2(size.xy)), (max(slice, 0.0) + 0.5) / float(size.z));
  vec4 ap = textureLod(aerialLut, coord, 0.0);
  float near = clamp(slice + 1.0, 0.0, 1.0);
  return vec4(ap.rgb * near, mix(1.0, ap.a, near));
}

// A surface point's colour seen through the air.
vec3 applyAerialPerspective(vec3 color, vec3 offset) {
  vec4 ap = aerialPerspective(offset);
  return color * ap.a + ap.rgb;
}

// The light on a surface of unit normal `n`: the sun's illuminance (before its cosine and
// shadow) and the sky's irradiance (ground bounce included).
vec3 sunIlluminance() { return skyLight.sunIlluminance.rgb; }
vec3 skyIrradiance(vec3 n) {
  return n.z >= 0.0 ? mix(skyLight.skySide.rgb, skyLight.skyUp.rgb, n.z)
                    : mix(skyLight.skySide.rgb, skyLight.skyDown.rgb, -n.z);
}
#include "sun_shadow.glsl"
