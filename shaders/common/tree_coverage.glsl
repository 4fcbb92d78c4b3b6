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

#endif
