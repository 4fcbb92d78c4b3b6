#ifndef TREE_CARD_SHAPE_GLSL
#define TREE_CARD_SHAPE_GLSL
// The trees' leaf cards' outlines (issue 20, issue 41 item 5), procedural in the card's uv (u
// across, v from the stem to the tip). Shared by C++ (render/tree_card_coverage.h bakes them into
// the mip levels of the cards' coverage texture, which tree.frag samples) and GLSL: keep to
// simulation/shared/glsl_compat.h's subset (f-suffixed literals, .x/.y only, VS_INLINE).
//
// A conifer card is a spray of needles: a twig along the card's middle and on each side one needle
// per row, leaning towards the tip, every needle with its own phase, lean and length (a hash of
// its row and side): no two rows repeat, so a card reads as a spray rather than as the regular
// chevrons of a sine. `detail` 1 draws the needles; 0 gives their mean coverage (a row finer than
// a pixel: the card seen from afar), so a distant crown keeps the coverage it has up close. A
// broadleaf card is a clump of three leaves.

// The coverage texture's level 0 (texels a side), and how many levels finer than the pixel's
// footprint tree.frag reads a conifer card (a texel a quarter of the pixel: tree_coverage.glsl).
const uint kTreeCardSize = 256u;
const uint kTreeCardFinerLevels = 2u;

const float kNeedleRows = 11.0f;
// The needles' mean where they give way (above their own share, about 0.55: sharpened, a distant
// card reads whole).
const float kNeedleMean = 0.8f;

// A needle's own numbers, 0 … 1: lowbias32 (Wellons) of its row and side, integer work only.
VS_INLINE float needleHash(float row, float side) {
  uint x = uint(int(row) * 2 + int(side)) + 0x9e3779b9u;
  x ^= x >> 16u;
  x *= 0x7feb352du;
  x ^= x >> 15u;
  x *= 0x846ca68bu;
  x ^= x >> 16u;
  return float(x >> 8u) * (1.0f / 16777216.0f);
}

// How far the rows lean towards the tip: rows per unit of the distance from the card's middle.
const float kNeedleLean = 2.2f;
// What a footprint of du × dv in uv spans of the needle rows' coordinate (v · kNeedleRows −
// across · kNeedleLean, across = 2 |u − ½|): its fwidth, the footprint the needles fade by.
VS_INLINE float needleRowsAcross(float du, float dv) { return kNeedleRows * dv + 2.0f * kNeedleLean * du; }

// The needles' detail for a footprint of `rowsPerPixel` needle rows (the row coordinate's change
// across one pixel, or one texel of a mip level): 1 up to a third of a row, 0 from 0.9 rows.
VS_INLINE float needleDetail(float rowsPerPixel) { return 1.0f - smoothstep(0.35f, 0.9f, rowsPerPixel); }

VS_INLINE float coniferNeedlesAt(vec2 uv, float detail) {
  float across = abs(uv.x - 0.5f) * 2.0f;
  float side = uv.x < 0.5f ? 0.0f : 1.0f;
  // The card itself is this trapezoid (vegetation/tree_model.cpp kConiferTipWidth).
  float width = 1.0f - 0.4f * uv.y;
  float inside = clamp((width - across) * 6.0f, 0.0f, 1.0f) * smoothstep(0.0f, 0.08f, uv.y);
  float twig = 1.0f - smoothstep(0.04f, 0.08f, across);
  float v = uv.y * kNeedleRows - across * kNeedleLean;  // rows lean towards the tip
  float row = floor(v);
  float h = needleHash(row, side);
  float g = needleHash(row + 17.0f, side);
  float f = v - row - 0.5f + 0.25f * (h - 0.5f) - 0.35f * (g - 0.5f) * across;  // phase and lean of this needle
  float len = mix(0.55f, 1.0f, g) * width;
  float needle = (1.0f - smoothstep(0.26f, 0.4f, abs(f))) * (1.0f - smoothstep(len - 0.1f, len, across));
  return inside * max(twig, mix(kNeedleMean, needle, detail));
}

VS_INLINE float broadleafClumpAt(vec2 uv) {
  float a = 0.0f;
  for (int i = 0; i < 3; ++i) {
    float ang = 1.0f + 2.0944f * float(i);
    vec2 c = vec2(0.5f, 0.5f) + vec2(cos(ang), sin(ang)) * 0.2f;
    vec2 axis = normalize(c - vec2(0.5f, 0.35f));
    vec2 q = uv - c;
    vec2 e = vec2(dot(q, axis) / 0.3f, dot(q, vec2(-axis.y, axis.x)) / 0.22f);
    a = max(a, 1.0f - dot(e, e));
  }
  return clamp(a * 4.0f, 0.0f, 1.0f);
}
#endif
