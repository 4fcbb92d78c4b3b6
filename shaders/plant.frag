#version 450
#extension GL_GOOGLE_include_directive : require
// Plant fragments: the colour comes lit from the vertices (common/plant_lighting.glsl, core seed
// 001_3eca9f2c7752e4fb.txt §2.4 eq. 13–14, evaluated once per vertex by the geometry stages or
// blades.comp), so what is left here is coverage. The blade's alpha mask becomes the fragment's
// MSAA sample mask (alpha-to-coverage, computed here: round(alpha · samples) samples, rotated and
// dithered per pixel so neighbours do not repeat one pattern; without MSAA it is an alpha test
// with the same dither); shadows are black at 35 % coverage (less where they fade out) — a screen door, no sorting. The
// fixed-function alphaToCoverageEnable is not used: lavapipe (Mesa 22.3) resolves such fragments
// to wrong, whitish colours, and a computed mask is the same on every device.
#include "frame_uniforms.glsl"
#include "philox.glsl"
#include "seeding.glsl"
#include "classify_layout.glsl"
#include "plant_common.glsl"
#include "aov.glsl"

layout(location = 0) in vec3 gColour;
layout(location = 1) in vec2 gBlade;
layout(location = 2) flat in uint gFlags;  // bits 0–1: kind (0 blade, 1 stone, 2 head); bit 2: shadow; bits 3–7: species
layout(location = 0) out vec4 outColor;

const float kShadowAlpha = 0.35;

// The 4 × 4 Bayer threshold of this pixel, in (0, 1): the coverage dither.
float ditherThreshold() {
  const float bayer[16] = float[16](0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5);
  ivec2 p = ivec2(gl_FragCoord.xy) & 3;
  return (bayer[p.y * 4 + p.x] + 0.5) / 16.0;
}

// A stone's outline in its diamond (x across, 2y − 1 up: the diamond |x| + |y| ≤ 1): a lumpy
// disc inside it instead of the diamond's corners, so gravel reads as pebbles, not tiles.
float pebbleEdge() {
  vec2 q = vec2(gBlade.x, 2.0 * gBlade.y - 1.0);
  return 0.64 + 0.06 * cos(3.0 * atan(q.y, q.x + 1e-6));
}

// The blade's detail texture (core seed 001 §2.4: a texture along the blade), procedural in the
// blade's own coordinates so it costs no fetch and looks the same at every distance: a lighter
// midrib, darker margins and faint parallel veins across the width, the lengthwise tone left to
// the per-vertex occlusion. 1 for stones and heads.
float bladeDetail(uint kind) {
  if (kind == 1u) {  // a stone: rounded, darker towards its rim
    vec2 q = vec2(gBlade.x, 2.0 * gBlade.y - 1.0);
    return 1.12 - 0.35 * dot(q, q);
  }
  if (kind != 0u) return 1.0;
  float ax = abs(gBlade.x);
  return 1.0 + 0.18 * (1.0 - smoothstep(0.0, 0.2, ax)) - 0.14 * smoothstep(0.4, 0.95, ax) +
         0.05 * cos(15.7 * gBlade.x);
}

void main() {
  bool shadow = (gFlags & 4u) != 0u;
  if (shadow && aovFrame()) discard;  // a shadow is not vegetation
  uint kind = gFlags & 3u;
  // The outline: a blade's soft edges, a flower head's disc, a stone's lumpy disc. A shadow is
  // drawn at 35 % coverage (less where it fades out: gColour.r, plant_shape.glsl), a head's and
  // a stone's in their outline (a blade's shadow is a streak a pixel or two wide: its whole quad).
  float r = length(vec2(gBlade.x, 2.0 * gBlade.y - 1.0));
  float shape = kind == 0u   ? 1.0 - smoothstep(0.6, 1.0, abs(gBlade.x))
                : kind == 2u ? 1.0 - smoothstep(0.75, 1.0, r)
                             : 1.0 - smoothstep(pebbleEdge() - 0.1, pebbleEdge(), r);
  float alpha = shadow ? kShadowAlpha * gColour.r * (kind == 0u ? 1.0 : shape) : shape;
  // Alpha to coverage: k of the n samples, k = ⌊alpha · n + dither⌋, starting at a per-pixel sample.
  uint samples = max((pc.flags >> 8) & 0xffu, 1u);
  float d = ditherThreshold();
  uint k = min(uint(alpha * float(samples) + d), samples);
  if (k == 0u) discard;
  uint first = uint(d * 16.0) % samples;
  uint bits = (k >= 32u ? 0xffffffffu : (1u << k) - 1u);
  uint mask = ((bits << first) | (bits >> (samples - first))) & ((samples >= 32u ? 0xffffffffu : (1u << samples) - 1u));
  if (mask == 0u) discard;
  gl_SampleMask[0] = int(mask);
  vec3 lit = (pc.flags & kFlagFlatColour) != 0u ? vec3(1.0, 0.0, 1.0) : gColour * bladeDetail(kind);
  outColor = aovFrame() ? aovVegetation(gFlags >> 3u) : vec4(shadow ? vec3(0.0) : lit, 1.0);
}
