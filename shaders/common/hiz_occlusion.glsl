#ifndef HIZ_OCCLUSION_GLSL
#define HIZ_OCCLUSION_GLSL
// Vertex stages: whether a bounding sphere is surely hidden behind the terrain, against this
// frame's Hi-Z pyramid (render/hiz_pass.h: per texel the FARTHEST depth of the terrain under it,
// reverse-Z; set 0 binding 6). It is, when its nearest depth is behind the farthest depth of
// every texel under its screen rectangle, at the level where that rectangle spans at most 2 × 2
// texels. Spheres reaching the near plane, or off screen, are never hidden; and nothing is hidden
// unless frame.terrainDepth.z says the pyramid holds this frame's terrain (it is built before
// the trees' scope when the terrain is shaded in compute). Needs frame_uniforms.glsl.

layout(std430, set = 0, binding = 6) readonly buffer HizPyramid { float hizPyramid[]; };

bool hiddenByTerrain(vec3 centre, float radius) {
  if (frame.terrainDepth.z == 0.0) return false;
  vec2 lo = vec2(1e30), hi = vec2(-1e30);
  float nearest = 0.0;
  for (int k = 0; k < 8; ++k) {
    vec3 corner = centre + radius * vec3((k & 1) != 0 ? 1.0 : -1.0, (k & 2) != 0 ? 1.0 : -1.0, (k & 4) != 0 ? 1.0 : -1.0);
    vec4 c = frame.viewProj * vec4(corner, 1.0);
    if (c.w <= 0.0 || c.z >= c.w) return false;  // reaches the near plane
    vec3 n = c.xyz / c.w;
    vec2 s = (n.xy * 0.5 + 0.5) * frame.viewport.xy;
    lo = min(lo, s);
    hi = max(hi, s);
    nearest = max(nearest, n.z);
  }
  lo = max(lo, vec2(0.0));
  hi = min(hi, frame.viewport.xy - 1.0);
  if (lo.x > hi.x || lo.y > hi.y) return false;  // off screen: the frustum test's business
  // Level l's texels cover 2^(l+1) pixels a side: the first that the rectangle spans ≤ 2 of.
  float extent = max(max(hi.x - lo.x, hi.y - lo.y), 1.0);
  int want = max(0, int(ceil(log2(extent))) - 1);
  uint w = uint(frame.viewport.x), h = uint(frame.viewport.y);
  uint offset = 0u, lw = 1u, lh = 1u;
  int level = 0;
  for (;; ++level) {  // render/hiz_pass.cpp hizLevels: the same sizes and offsets
    lw = (w + (2u << level) - 1u) >> (level + 1);
    lh = (h + (2u << level) - 1u) >> (level + 1);
    if (level == want || (lw == 1u && lh == 1u)) break;
    offset += lw * lh;
  }
  uvec2 t0 = uvec2(lo) >> uint(level + 1), t1 = min(uvec2(hi) >> uint(level + 1), uvec2(lw - 1u, lh - 1u));
  float farthest = 1.0;
  for (uint y = t0.y; y <= t1.y; ++y)
    for (uint x = t0.x; x <= t1.x; ++x) farthest = min(farthest, hizPyramid[offset + y * lw + x]);
  return nearest < farthest;
}
#endif
