#version 450
// The frame's sky-view LUT and aerial-perspective volume (Hillaire 2020 §5.3–5.4; render/
// atmosphere_pass.h), both in the sun-relative direction mapping of skyViewDirectionFromUv seen
// from the camera's altitude. z = 0 of the dispatch: the sky-view texel (the whole ray, 32 steps);
// otherwise column (x, y) of the aerial volume: the ray marched slice by slice, slice k ending at
// far · ((k + 1) / slices)², storing the in-scattered luminance and the mean transmittance.
#extension GL_GOOGLE_include_directive : require
#include "common/atmosphere_lut_io.glsl"
layout(local_size_x = 8, local_size_y = 8) in;

AtmosphereRay viewRay(vec2 uv) {
  vec2 dir = skyViewDirectionFromUv(pc.view.x, uv);  // (cos zenith, azimuth from the sun)
  float muS = pc.view.y;
  float sinS = sqrt(max(1.0 - muS * muS, 0.0));
  float sinV = sqrt(max(1.0 - dir.x * dir.x, 0.0));
  return AtmosphereRay(pc.view.x, dir.x, muS, sinV * cos(dir.y) * sinS + dir.x * muS);
}

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  bool multiple = pc.view.w > 0.5;
  if (gl_GlobalInvocationID.z == 0u) {
    ivec2 size = imageSize(skyViewOut);
    if (texel.x >= size.x || texel.y >= size.y) return;
    vec3 l = skyLuminanceMarched(viewRay(lutUvOfTexel(texel, size)), 32, multiple);
    imageStore(skyViewOut, texel, vec4(l, 1.0));
    return;
  }
  ivec3 size = imageSize(aerialOut);
  if (texel.x >= size.x || texel.y >= size.y) return;
  AtmosphereRay ray = viewRay(lutUvOfTexel(texel, size.xy));
  vec3 luminance = vec3(0.0), transmittance = vec3(1.0);
  float t0 = 0.0;
  for (int k = 0; k < size.z; ++k) {
    float w = (float(k) + 1.0) / float(size.z);
    float t1 = pc.view.z * w * w;
    marchSegment(ray, t0, t1, 2, multiple, luminance, transmittance);
    imageStore(aerialOut, ivec3(texel, k), vec4(luminance, dot(transmittance, vec3(1.0 / 3.0))));
    t0 = t1;
  }
}
