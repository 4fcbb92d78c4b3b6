#ifndef TREE_COVERAGE_GLSL
#define TREE_COVERAGE_GLSL
// Fragment stages only (fwidth): tree.frag and tree_impostor.frag.

// Coverage from an alpha sharpened to the pixel's footprint (Golus 2017, "Anti-aliased alpha
// test"): a crisp outline at `edge`, antialiased by the coverage mask, and no fragment kept for a
// faint fringe — on the H200 every fragment kept costs its samples whether it covers one or four.
// Where the pattern is finer than a pixel (fwidth near 1) the plain alpha is the better estimate:
// sharpening would round it towards one half. Call in uniform control flow (fwidth).
float treeSharpCoverage(float alpha, float edge) {
  float footprint = fwidth(alpha);
  return mix(clamp((alpha - edge) / max(footprint, 1e-4) + 0.5, 0.0, 1.0), alpha, smoothstep(0.3, 1.0, footprint));
}

// The cards' outlines (common/tree_card_shape.glsl), baked into a coverage texture at start-up
// (render/tree_card_coverage.h): layer 0 a conifer's needles, layer 1 a broadleaf's clump, each
// mip level the box-filtered coverage of the texels it covers, the needles giving way to their
// mean where a level's texel spans a third of a needle row or more (needleDetail) — the fade the
// fragment stage used to compute from fwidth of the row coordinate, now chosen by the sampler's
// level. One filtered read instead of two integer hashes and six smoothsteps a fragment: the H200
// runs the trees' fragments on a few of its units (tree_shading.glsl).
#include "simulation/shared/shared_code_macros.glsl"
#include "tree_card_shape.glsl"
layout(set = 1, binding = 10) uniform sampler2DArray treeCards;

// A card's coverage, 0 … 1, at its uv. `form` (the model's: 0 conifer, 1 broadleaf) is uniform
// over the draw. A conifer's level follows what the pixel spans of the needle rows' coordinate
// (tree_card_shape.glsl needleRowsAcross), the footprint the fragment stage faded the
// needles by, not the sampler's largest one (a card seen edge on across its width keeps its
// needles), and is kTreeCardFinerLevels finer than that footprint: a texel a quarter of the
// pixel, close to the point the outline was evaluated at, so the gaps between needles stay open
// until the needles fade, as they did (a level as coarse as the pixel fills them: its mean, about
// 0.7, sharpens to a solid slab). Call in uniform control flow (derivatives).
float treeCardCoverage(vec2 uv, float form) {
  vec2 fw = fwidth(uv);
  if (form >= 0.5) return texture(treeCards, vec3(uv, 1.0)).r;
  float rowsPerTexel = needleRowsAcross(1.0, 1.0) / float(kTreeCardSize);  // at level 0
  float level = log2(max(needleRowsAcross(fw.x, fw.y) / rowsPerTexel, 1e-6)) - float(kTreeCardFinerLevels);
  return textureLod(treeCards, vec3(uv, 0.0), level).r;
}

#endif
