#version 450
#extension GL_GOOGLE_include_directive : require
#include "frame_uniforms.glsl"
#include "atmosphere.glsl"
#include "colour_score.glsl"
#include "terrain_detail.glsl"
#include "terrain_palette.glsl"
#include "terrain_push.glsl"
layout(set = 1, binding = 0) uniform sampler2DArray imagery;  // one tile per layer; sRGB: sampled as linear colour
layout(set = 2, binding = 0) uniform sampler2DArray detailTextures;  // one layer per detail surface; UNORM, 0.5 = neutral
layout(location = 0) in vec3 inOffset;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in float inHeightMsl;
layout(location = 3) in vec2 inUv;
layout(location = 0) out vec4 outColor;

// Imagery is a photograph: it already holds the sun and shadows of its day. Treat it as
// albedo times the light it was taken under (roughly the average lighting), so relighting with
// our sun keeps its brightness rather than doubling the shading.
const float kImageryExposure = 1.6;

// Close-up detail (core seed 001 §3.3): the detail surfaces blended by the colour-score weights
// of the base colour, as a factor on the albedo (2 × texel: 0.5 is neutral). Tiled in world
// space — frame.detail holds the camera position modulo the period, so the pattern does not swim
// — at two scales, projected triplanar so cliffs are not smeared, and faded out with distance so
// far terrain is exactly the imagery. `world`, `dx`, `dy`: position in periods and its screen
// derivatives (taken in uniform control flow by the caller).
vec3 detailFactor(vec3 baseLinear, vec3 n, vec3 world, vec3 dx, vec3 dy) {
  float fade = (1.0 - smoothstep(detail.params.y, detail.params.z, length(inOffset))) * detail.params.w * frame.detail.w;
  if (fade <= 0.0) return vec3(1.0);
  vec4 surfaces = detailSurfaceWeights(hsvFromLinear(baseLinear));
  vec3 planes = pow(abs(n), vec3(4.0));
  planes /= planes.x + planes.y + planes.z;  // x: the yz plane, y: xz, z: xy (flat ground)
  float fine = detail.tiling.y, coarse = detail.tiling.z, coarseShare = detail.tiling.w;
  vec3 factor = vec3(0.0);
  for (int layer = 0; layer < kDetailSurfaces; ++layer) {
    float w = surfaces[layer];
    if (w < 1e-3) {  // negligible: count it as neutral rather than sample it
      factor += w;
      continue;
    }
    vec3 texel = vec3(0.0);
    for (int axis = 0; axis < 3; ++axis) {
      if (planes[axis] < 1e-3) continue;
      vec2 uv = axis == 0 ? world.yz : (axis == 1 ? world.xz : world.xy);
      vec2 ux = axis == 0 ? dx.yz : (axis == 1 ? dx.xz : dx.xy);
      vec2 uy = axis == 0 ? dy.yz : (axis == 1 ? dy.xz : dy.xy);
      vec3 a = textureGrad(detailTextures, vec3(uv * fine, layer), ux * fine, uy * fine).rgb;
      vec3 b = textureGrad(detailTextures, vec3(uv * coarse, layer), ux * coarse, uy * coarse).rgb;
      texel += planes[axis] * mix(a, b, coarseShare);
    }
    factor += w * 2.0 * texel;
  }
  return mix(vec3(1.0), factor, fade);
}

void main() {
  vec3 n = normalize(inNormal);
  vec3 world = (frame.detail.xyz + inOffset) / detail.tiling.x;
  vec3 dx = dFdx(world), dy = dFdy(world);
  float slope = 1.0 - clamp(n.z, 0.0, 1.0);  // 0 flat … 1 vertical
  vec3 albedo = terrainAlbedo(inHeightMsl, slope);
  vec3 base = albedo;  // the ground's colour as imaged: what the colour score reads
  if (push.layers.x >= 0.0) {
    vec4 photo = texture(imagery, vec3(inUv * push.imageryUv.xy + push.imageryUv.zw, push.layers.x));
    if (push.layers.y >= 0.0 && push.layers.z < 1.0) {  // a finer tile fading in over its ancestor
      vec4 before = texture(imagery, vec3(inUv * push.previousUv.xy + push.previousUv.zw, push.layers.y));
      photo = mix(before, photo, push.layers.z);
    }
    base = mix(albedo, photo.rgb, photo.a);
    albedo = mix(albedo, photo.rgb * kImageryExposure * 0.5, photo.a);  // alpha 0: no imagery there
  }
  albedo *= detailFactor(base, n, world, dx, dy);
  float sun = max(dot(n, frame.sunDirection.xyz), 0.0);
  // Hemispherical sky light: full from above, half from the horizon.
  vec3 ambient = mix(frame.skyHorizon.rgb, frame.skyZenith.rgb, 0.5) * (0.5 + 0.5 * n.z) * 0.35;
  vec3 lit = albedo * (frame.sunColor.rgb * sun + ambient);
  outColor = vec4(applyAerialPerspective(lit, inOffset), 1.0);
}
