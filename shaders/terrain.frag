#version 450
#extension GL_GOOGLE_include_directive : require
#include "frame_uniforms.glsl"
#include "atmosphere.glsl"
#include "terrain_palette.glsl"
#include "terrain_push.glsl"
layout(set = 1, binding = 0) uniform sampler2DArray imagery;  // one tile per layer; sRGB: sampled as linear colour
layout(location = 0) in vec3 inOffset;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in float inHeightMsl;
layout(location = 3) in vec2 inUv;
layout(location = 0) out vec4 outColor;

// Imagery is a photograph: it already holds the sun and shadows of its day. Treat it as
// albedo times the light it was taken under (roughly the average lighting), so relighting with
// our sun keeps its brightness rather than doubling the shading.
const float kImageryExposure = 1.6;

void main() {
  vec3 n = normalize(inNormal);
  float slope = 1.0 - clamp(n.z, 0.0, 1.0);  // 0 flat … 1 vertical
  vec3 albedo = terrainAlbedo(inHeightMsl, slope);
  if (push.layers.x >= 0.0) {
    vec4 photo = texture(imagery, vec3(inUv * push.imageryUv.xy + push.imageryUv.zw, push.layers.x));
    if (push.layers.y >= 0.0 && push.layers.z < 1.0) {  // a finer tile fading in over its ancestor
      vec4 before = texture(imagery, vec3(inUv * push.previousUv.xy + push.previousUv.zw, push.layers.y));
      photo = mix(before, photo, push.layers.z);
    }
    albedo = mix(albedo, photo.rgb * kImageryExposure * 0.5, photo.a);  // alpha 0: no imagery there
  }
  float sun = max(dot(n, frame.sunDirection.xyz), 0.0);
  // Hemispherical sky light: full from above, half from the horizon.
  vec3 ambient = mix(frame.skyHorizon.rgb, frame.skyZenith.rgb, 0.5) * (0.5 + 0.5 * n.z) * 0.35;
  vec3 lit = albedo * (frame.sunColor.rgb * sun + ambient);
  outColor = vec4(applyAerialPerspective(lit, inOffset), 1.0);
}
