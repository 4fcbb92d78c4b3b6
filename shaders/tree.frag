#version 460
#extension GL_GOOGLE_include_directive : require
// Tree models' fragments (issue 20): bark and leaf or needle cards (their outline procedural, in
// the card's uv), the level-of-detail cross-fade as a dither (common/tree_layout.glsl), alpha to
// coverage (sharpened) into the sample mask, and the lighting of common/tree_shading.glsl. Capture modes write
// what the impostors keep (mode 2): albedo (darkened by the crown's occlusion) and coverage, and the
// model-space normal and depth. The capture draws the crown's core too (kind 2: opaque, shaded
// as tree_core.frag, which draws it in colour).
#include "common/frame_uniforms.glsl"
#include "common/atmosphere.glsl"
#include "common/tree_layout.glsl"
#include "common/aov.glsl"
#include "common/tree_push.glsl"
#include "common/tree_shading.glsl"
#include "common/tree_coverage.glsl"

layout(location = 0) in vec3 vPos;
layout(location = 1) in vec3 vNormal;
layout(location = 2) in vec2 vUv;
layout(location = 3) flat in uint vKind;
layout(location = 4) flat in float vThreshold;
layout(location = 5) flat in uint vInstance;
layout(location = 6) in float vOcclusion;
layout(location = 7) flat in vec4 vColour;
layout(location = 8) in vec2 vCell;
layout(location = 9) in vec4 vSky;
layout(location = 10) in float vSun;
layout(location = 0) out vec4 outColor;
layout(location = 1) out vec4 outNormalDepth;  // capture only

void main() {
  // The colour path writes its own coverage; every other path covers all samples (a shader that
  // writes gl_SampleMask on one path leaves it undefined on the others: lavapipe drops them).
  gl_SampleMask[0] = -1;
  TreeModelGpu m = trees.models[push.model];
  bool leaf = vKind == 1u;
  float alpha = treeSharpCoverage(leaf ? treeCardShape(vUv, m.bark.w, push.mode == 1u ? 0.0 : 1.0) : 1.0, 0.5);
  if (push.mode >= 2u) {  // impostor capture (4 samples, averaged): the card's alpha as coverage, unlit
    if (any(greaterThan(abs(vCell), vec2(1.0)))) discard;  // outside this view's cell
    uint mask = treeSampleMask(alpha, push.samples, 0.5);
    if (mask == 0u) discard;
    gl_SampleMask[0] = int(mask);
    vec3 n = normalize(vNormal);
    if (!gl_FrontFacing) n = -n;
    vec3 albedo = vKind == 2u ? m.leaf.rgb * kTreeCoreShade : (leaf ? m.leaf.rgb : m.bark.rgb);
    outColor = vec4(albedo * mix(0.35, 1.0, vOcclusion), 1.0);
    outNormalDepth = vec4(n * 0.5 + 0.5, gl_FragCoord.z);
    return;
  }
  float dither = treeDither(gl_FragCoord.xy, vInstance);
  if (!treeKeepsPixel(vThreshold, dither)) discard;
  if (dither >= treeNearKeep(vPos)) discard;  // the near fade
  uint mask = treeSampleMask(alpha, push.samples, fract(dither * 7.0 + 0.31));
  if (mask == 0u) discard;
  gl_SampleMask[0] = int(mask);
  vec3 n = normalize(vNormal);
  if (!gl_FrontFacing) n = -n;
  vec3 albedo = (leaf ? vColour.rgb : m.bark.rgb) * vColour.a;
  if (!leaf) albedo *= 0.85 + 0.3 * fract(sin(floor(vUv.y * 6.0) * 12.9898) * 43758.5453);  // bark bands
  vec3 lit = treeLight(n, albedo, m.leaf.w, leaf, vOcclusion, vSun);
  outColor = aovFrame() ? aovVegetation(m.ids.x) : vec4(lit * vSky.a + vSky.rgb, 1.0);
}
