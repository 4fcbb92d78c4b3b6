// The atmosphere LUT passes' bindings (render/atmosphere_pass.h) and the GPU's lookups that
// atmosphere_march.glsl reads. Texel i of a LUT n texels wide holds u = i / (n − 1), so u = 0
// and 1 are texel centres.
#include "simulation/shared/shared_code_macros.glsl"
#include "atmosphere_model.glsl"

layout(set = 0, binding = 0) uniform sampler2D transmittanceLut;
layout(set = 0, binding = 1) uniform sampler2D multiScatteringLut;
layout(set = 0, binding = 2, rgba16f) uniform writeonly image2D transmittanceOut;
layout(set = 0, binding = 3, rgba16f) uniform writeonly image2D multiScatteringOut;
layout(set = 0, binding = 4, rgba16f) uniform writeonly image2D skyViewOut;
layout(set = 0, binding = 5, rgba16f) uniform writeonly image3D aerialOut;
layout(set = 0, binding = 6) uniform sampler2D skyViewLut;
layout(set = 0, binding = 7, std430) writeonly buffer SkyLightOut {
  vec4 sunIlluminance;  // rgb at the camera; w: the sun's cosine with the up
  vec4 skyUp;           // irradiance from the sky on an upward surface
  vec4 skySide;         // … on a vertical one (averaged over its azimuth)
  vec4 skyDown;         // … on a downward one (the lit ground's bounce)
} skyLightOut;
layout(push_constant) uniform AtmospherePush {
  vec4 view;  // x: the camera's radius (km), y: the sun's cosine with the up, z: aerial LUT's far distance (km), w: 1 = multiple scattering
} pc;

vec2 lutTexelUv(vec2 uv, vec2 size) { return (uv * (size - 1.0) + 0.5) / size; }
vec2 lutUvOfTexel(ivec2 texel, ivec2 size) { return vec2(texel) / vec2(size - 1); }

vec3 sunTransmittance(float r, float muS) {
  if (rayHitsGround(r, muS)) return vec3(0.0);
  vec2 uv = transmittanceUvFromRMu(r, muS);
  return textureLod(transmittanceLut, lutTexelUv(uv, vec2(textureSize(transmittanceLut, 0))), 0.0).rgb;
}
vec3 multiScattering(float r, float muS) {
  vec2 uv = multiScatteringUvFromRMuS(r, muS);
  return textureLod(multiScatteringLut, lutTexelUv(uv, vec2(textureSize(multiScatteringLut, 0))), 0.0).rgb;
}

#include "atmosphere_march.glsl"
