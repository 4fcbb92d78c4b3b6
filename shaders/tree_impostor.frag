#version 460
#extension GL_GOOGLE_include_directive : require
// Octahedral impostors' fragments (issue 20): the captured albedo and coverage, and the captured
// model-space normal turned into the world, lit at run time like the models (common/tree_shading.glsl)
// with the cross-fade dither and alpha to coverage of tree.frag. (The shadow cascades draw the
// impostors in compute: tree_shadow_raster.comp.)
#include "common/frame_uniforms.glsl"
#include "common/atmosphere.glsl"
#include "common/tree_layout.glsl"
#include "common/aov.glsl"
#include "common/tree_push.glsl"
#include "common/tree_shading.glsl"
#include "common/tree_coverage.glsl"

layout(set = 1, binding = 8) uniform sampler2DArray impostorAlbedo;
layout(set = 1, binding = 9) uniform sampler2DArray impostorNormal;

layout(location = 0) in vec3 vPos;
layout(location = 1) in vec2 vUv;
layout(location = 2) flat in uint vLayer;
layout(location = 3) flat in float vThreshold;
layout(location = 4) flat in uint vInstance;
layout(location = 5) flat in vec3 vRotX;  // the tree's turn (tree_impostor.vert)
layout(location = 6) flat in vec3 vRotY;
layout(location = 7) flat in vec3 vTowards;
layout(location = 8) flat in vec3 vTint;
layout(location = 9) flat in vec3 vRotZ;
layout(location = 10) flat in vec4 vSky;
layout(location = 11) flat in float vSun;
layout(location = 12) flat in vec4 vRect;
layout(location = 0) out vec4 outColor;

void main() {
  gl_SampleMask[0] = -1;  // as tree.frag: defined on every path
  // The triangle reaches past the rectangle the model fills (and its atlas cell): not drawn.
  if (any(greaterThan(abs(vUv - vRect.xy), vRect.zw))) discard;
  vec4 albedo = texture(impostorAlbedo, vec3(vUv, float(vLayer)));
  // The coverage sharpened as tree.frag's cards. The edge at 0.57, not 0.5: magnified, the
  // averaged atlas fills needle gaps narrower than its texels, and the impostor drew 5 % more than
  // the conifer model at the switch (tree_render_test.cpp). Minified, a texel of a coarser level
  // holds the share of the crown's cells the needles cover, gaps between whorls included: the
  // edge falls to 0.3 over the first two levels, so a crown seen from afar reads as a crown (its
  // layers of branches, one behind the other, close what one layer leaves open), as the cards'
  // needles give way to a mean of 0.8 (common/tree_coverage.glsl).
  float lod = clamp(textureQueryLod(impostorAlbedo, vUv).y, 0.0, 2.0);
  float coverage = treeSharpCoverage(albedo.a, mix(0.57, 0.3, 0.5 * lod));
  float dither = treeDither(gl_FragCoord.xy, vInstance);
  if (!treeKeepsPixel(vThreshold, dither)) discard;
  uint mask = treeSampleMask(coverage, push.samples, fract(dither * 7.0 + 0.31));
  if (mask == 0u) discard;
  gl_SampleMask[0] = int(mask);
  // Premultiplied by the coverage (the capture averaged its samples with the empty background).
  vec3 nm = texture(impostorNormal, vec3(vUv, float(vLayer))).xyz / max(albedo.a, 1e-3) * 2.0 - 1.0;
  vec3 n = normalize(mat3(vRotX, vRotY, vRotZ) * nm);
  if (dot(n, vTowards) < 0.0) n = -n;
  TreeModelGpu m = trees.models[push.model];
  // The capture holds the species' leaf colour: turned into this tree's (treeLeafAlbedo).
  vec3 colour = albedo.rgb / max(albedo.a, 1e-3) * vTint;
  vec3 lit = treeLight(n, colour, m.leaf.w, true, 1.0, vSun);
  outColor = aovFrame() ? aovVegetation(m.ids.x) : vec4(lit * vSky.a + vSky.rgb, 1.0);
}
