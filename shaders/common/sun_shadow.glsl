#ifndef SUN_SHADOW_GLSL
#define SUN_SHADOW_GLSL
// The sun's cascaded shadow map (issue 20, render/sun_shadow_pass.h, render/shadow_cascades.h):
// set 0, binding 4, one layer per cascade, reverse-Z (1 nearest the sun) as the bits of a float
// in an R32_UINT image (the trees are rasterised into it in compute with atomic max:
// tree_shadow_raster.comp), read four texels at a time (textureGather) and compared here
// (GREATER_OR_EQUAL: lit where the point is at least as near the sun as the nearest caster), the
// comparisons filtered bilinearly as a comparison sampler filters them. Needs frame_uniforms.glsl.
//
// Bias (issue 39 item 8): normal-offset shadows (Holbert, "Saying Goodbye to Shadow Acne", GDC
// 2011; "Normal Offset Shadows", 2010): the receiver moves along its normal by a texel of its
// cascade times (½ + sin θ), θ between normal and sun, so a slope leaning away from the sun
// leaves its own texels; plus a slope-scaled depth bias (tan θ texels, capped at 4) that covers
// the plane's depth change across the filter's reach. Isidoro's receiver-plane depth bias (GDC
// 2006) needs screen derivatives, which the vertex and compute stages that call this lack.
// Filter: a 3 × 3 tent PCF from four bilinear comparison taps half a texel off the point
// (Castaño, "Shadow Mapping Summary", 2013): a fixed pattern, so frames stay deterministic; a
// caster a texel thin still darkens its texels by half, continuous, not in dashes.
layout(set = 0, binding = 4) uniform usampler2DArray sunShadowMap;

// A bilinear comparison tap at `uv` of layer `layer`: the 2 × 2 texels a linear filter reads
// there, each lit (1) where `z` is at least their depth, weighted as the filter weights them.
float sunShadowTap(vec2 uv, float layer, float z, vec2 size) {
  uvec4 texels = textureGather(sunShadowMap, vec3(uv, layer));  // (0, 1), (1, 1), (1, 0), (0, 0)
  vec4 lit = vec4(greaterThanEqual(vec4(z), uintBitsToFloat(texels)));
  vec2 f = fract(uv * size - 0.5);
  return mix(mix(lit.w, lit.z, f.x), mix(lit.x, lit.y, f.x), f.y);
}

// 1 sunlit … 0 in shadow, at camera-relative `pos` with unit `normal`.
float sunShadow(vec3 pos, vec3 normal) {
  if (frame.shadowSplits.w < 0.5) return 1.0;
  float depth = (frame.viewProj * vec4(pos, 1.0)).w;  // the view distance along the axis
  int c = depth < frame.shadowSplits.x ? 0 : (depth < frame.shadowSplits.y ? 1 : (depth < frame.shadowSplits.z ? 2 : 3));
  if (c == 3) return 1.0;
  float texel = frame.shadowTexel[c];
  float cosT = clamp(dot(normal, frame.sunDirection.xyz), 0.05, 1.0), sinT = sqrt(1.0 - cosT * cosT);
  mat4 m = frame.shadowMatrices[c];
  vec4 s = m * vec4(pos + normal * (texel * 0.5 * sinT), 1.0);
  // Depth per metre towards the sun: the matrix's third row.
  float perMetre = length(vec3(m[0][2], m[1][2], m[2][2]));
  float bias = perMetre * texel * (1.0 + min(sinT / cosT, 4.0));
  vec2 size = vec2(textureSize(sunShadowMap, 0).xy);
  vec2 uv = s.xy * 0.5 + 0.5;
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return 1.0;
  vec2 h = 0.5 / size;
  float z = s.z + bias;
  float lit = 0.25 * (sunShadowTap(uv + vec2(-h.x, -h.y), float(c), z, size) +
                      sunShadowTap(uv + vec2(h.x, -h.y), float(c), z, size) +
                      sunShadowTap(uv + vec2(-h.x, h.y), float(c), z, size) +
                      sunShadowTap(uv + vec2(h.x, h.y), float(c), z, size));
  // The last cascade fades out over its last tenth, so the shadows' end is no line.
  float fade = c == 2 ? clamp((frame.shadowSplits.z - depth) / (0.1 * frame.shadowSplits.z), 0.0, 1.0) : 1.0;
  return mix(1.0, lit, fade);
}
#endif
