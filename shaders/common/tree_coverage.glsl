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

// A conifer card's needles (issue 41 item 5): a twig along the card's middle and on each side one
// needle per row, leaning towards the tip, every needle with its own phase, lean and length (a
// hash of its row and side): no two rows repeat, so a card reads as a spray rather than as the
// regular chevrons of a sine. Where a row is finer than about a pixel (fwidth of the row
// coordinate: the card seen from afar, its mip level as it were) the needles give way to their
// mean coverage, so a distant crown keeps the coverage it has up close; `fine` 0 takes the mean
// everywhere (the shadow maps: a needle's shadow is finer than their texels, and a lone tree's
// shadow must stay one piece). Call in uniform control flow (fwidth).
const float kNeedleRows = 11.0;
// A needle's own numbers, 0 … 1: lowbias32 (Wellons) of its row and side, integer work only (a
// sine hash costs the fragment stage's special-function units, its scarcest).
float needleHash(float row, float side) {
  uint x = uint(int(row) * 2 + int(side)) + 0x9e3779b9u;
  x ^= x >> 16; x *= 0x7feb352du; x ^= x >> 15; x *= 0x846ca68bu; x ^= x >> 16;
  return float(x >> 8) * (1.0 / 16777216.0);
}
float coniferNeedles(vec2 uv, float fine) {
  float across = abs(uv.x - 0.5) * 2.0;
  float side = uv.x < 0.5 ? 0.0 : 1.0;
  float width = 1.0 - 0.4 * uv.y;  // the card itself is this trapezoid (vegetation/tree_model.cpp kConiferTipWidth)
  float inside = clamp((width - across) * 6.0, 0.0, 1.0) * smoothstep(0.0, 0.08, uv.y);
  float twig = 1.0 - smoothstep(0.04, 0.08, across);
  float v = uv.y * kNeedleRows - across * 2.2;  // rows lean towards the tip
  float row = floor(v);
  float h = needleHash(row, side), g = needleHash(row + 17.0, side);
  float f = v - row - 0.5 + 0.25 * (h - 0.5) - 0.35 * (g - 0.5) * across;  // phase and lean of this needle
  float len = mix(0.55, 1.0, g) * width;
  float needle = (1.0 - smoothstep(0.26, 0.4, abs(f))) * (1.0 - smoothstep(len - 0.1, len, across));
  float detail = fine * (1.0 - smoothstep(0.35, 0.9, fwidth(v)));
  float mean = 0.8;  // above the needles' own share (~0.55): sharpened, a distant card (and a shadow) reads whole
  return inside * max(twig, mix(mean, needle, detail));
}

// A card's coverage, 0 … 1, in its uv (u across, v from the stem to the tip). Conifer: a spray of
// needles, narrowing to the tip; broadleaf: a clump of three leaves. `fine`: coniferNeedles'.
// Call in uniform control flow, with `form` uniform over the draw (the model's): the branch on it
// keeps coniferNeedles' fwidth in uniform control flow, and a broadleaf's fragments skip it.
float treeCardShape(vec2 uv, float form, float fine) {
  if (form < 0.5) return coniferNeedles(uv, fine);
  float a = 0.0;
  for (int i = 0; i < 3; ++i) {
    float ang = 1.0 + 2.0944 * float(i);
    vec2 c = vec2(0.5, 0.5) + 0.2 * vec2(cos(ang), sin(ang));
    vec2 axis = normalize(c - vec2(0.5, 0.35));
    vec2 q = uv - c;
    vec2 e = vec2(dot(q, axis), dot(q, vec2(-axis.y, axis.x))) / vec2(0.3, 0.22);
    a = max(a, 1.0 - dot(e, e));
  }
  return clamp(a * 4.0, 0.0, 1.0);
}


#endif
