#ifndef SUN_SHADOW_GLSL
#define SUN_SHADOW_GLSL
// The sun's cascaded shadow map (issue 20, render/sun_shadow_pass.h, render/shadow_cascades.h):
// set 0, binding 4, one layer per cascade, reverse-Z (1 nearest the sun), a comparison sampler
// (GREATER_OR_EQUAL: lit where the point is at least as near the sun as the nearest caster) with
// bilinear filtering: 2 × 2 percentage-closer filtering in hardware. Needs frame_uniforms.glsl.
layout(set = 0, binding = 4) uniform sampler2DArrayShadow sunShadowMap;

// 1 sunlit … 0 in shadow, at camera-relative `pos` with unit `normal` (the receiver is pushed
// along its normal by 1.5 texels of its cascade: no acne on slopes facing the sun).
float sunShadow(vec3 pos, vec3 normal) {
  if (frame.shadowSplits.w < 0.5) return 1.0;
  float depth = (frame.viewProj * vec4(pos, 1.0)).w;  // the view distance along the axis
  int c = depth < frame.shadowSplits.x ? 0 : (depth < frame.shadowSplits.y ? 1 : (depth < frame.shadowSplits.z ? 2 : 3));
  if (c == 3) return 1.0;
  float texel = frame.shadowTexel[c];
  vec4 s = frame.shadowMatrices[c] * vec4(pos + normal * (1.5 * texel), 1.0);
  vec2 uv = s.xy * 0.5 + 0.5;
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return 1.0;
  float lit = texture(sunShadowMap, vec4(uv, float(c), s.z + 2e-5));
  // The last cascade fades out over its last tenth, so the shadows' end is no line.
  float fade = c == 2 ? clamp((frame.shadowSplits.z - depth) / (0.1 * frame.shadowSplits.z), 0.0, 1.0) : 1.0;
  return mix(1.0, lit, fade);
}
#endif
