#version 450
#extension GL_GOOGLE_include_directive : require
// Occlusion culling of seed triangles against the Hi-Z pyramid (render/hiz_pass.h) — the
// hierarchical Z-buffer of Greene, Kass & Miller, "Hierarchical Z-Buffer Visibility",
// SIGGRAPH 1993: a box is hidden when its nearest depth lies behind the farthest depth of the
// pyramid texels that cover its screen rectangle. One thread per seed triangle, before the
// classify pass expands it: visible[t] has bit s set when plants of species s on t may show;
// visible[t] = 0 means no cluster of t is classified or drawn, and classify.comp drops the
// groups whose species' bit is clear (behind a ridge that hides grass but not trees).
//
// The bound must hold everything a species' plants can put on screen: the roots lie in the
// triangle; a plant reaches at most reach[s] metres from its root in any direction (height,
// width and lean: render/hiz_pass.cpp speciesReach; plus the minimum on-screen width) — box 1;
// its planar shadow (core seed 001 §3.6, common/plant_geometry.glsl) is that geometry projected
// along the sunlight onto the triangle's plane — box 2, flat on the ground. Hidden = both boxes
// hidden. Anything we are unsure of is kept.
layout(local_size_x = 64) in;

#include "frame_uniforms.glsl"
#include "classify_layout.glsl"
#include "philox.glsl"
#include "seeding.glsl"
#include "depth_tile_marks.glsl"

layout(set = 1, binding = 0, std430) readonly buffer Triangles { SeedTriangle triangles[]; };
layout(set = 1, binding = 1, std430) writeonly buffer Visible { uint visible[]; };
// tested: triangles with plants; culled: those hidden for every species; clustersCulled: their
// classify work items (seeds of cluster 0 + further clusters, vegetation::classifyItems);
// plantsCulled: Σ ceil(N) over them.
layout(set = 1, binding = 2, std430) buffer Counters { uint tested, culled, clustersCulled, plantsCulled; };
layout(set = 1, binding = 3, std430) readonly buffer Hiz { float hiz[]; };

layout(push_constant) uniform Push {
  uint count;          // seed triangles
  uint clusterSize;    // C
  uint shadows;        // 1: planar shadows are drawn
  uint width, height;  // pixels of the depth target
  uint levels;         // Hi-Z levels; level l has ceil(width / 2^(l+1)) × ceil(height / 2^(l+1)) texels
  uint species;        // species in the catalog
  uint drawn;          // the species the plant pass draws (bits): only theirs are marked
  float reach[kMaxSpecies];  // m per species; < 0: bare soil (never drawn)
} pc;

uint levelW(uint l) { return (pc.width + (2u << l) - 1u) >> (l + 1u); }
uint levelH(uint l) { return (pc.height + (2u << l) - 1u) >> (l + 1u); }
uint levelOffset(uint l) {
  uint o = 0u;
  for (uint i = 0u; i < l; ++i) o += levelW(i) * levelH(i);
  return o;
}

// True when the box [lo, hi] (camera-relative) is certainly hidden behind this frame's depth.
bool boxHidden(vec3 lo, vec3 hi) {
  vec2 pmin = vec2(1e30), pmax = vec2(-1e30);
  float nearest = 0.0;  // reverse-Z: the largest depth of the box
  for (int i = 0; i < 8; ++i) {
    vec3 c = vec3((i & 1) != 0 ? hi.x : lo.x, (i & 2) != 0 ? hi.y : lo.y, (i & 4) != 0 ? hi.z : lo.z);
    vec4 clip = frame.viewProj * vec4(c, 1.0);
    if (clip.w <= 0.0 || clip.z >= clip.w) return false;  // reaches the near plane or behind the eye
    vec3 ndc = clip.xyz / clip.w;
    vec2 px = (ndc.xy * 0.5 + 0.5) * vec2(pc.width, pc.height);
    pmin = min(pmin, px);
    pmax = max(pmax, px);
    nearest = max(nearest, ndc.z);
  }
  // Entirely off screen: the terrain's frustum culling decides that, not this test.
  if (pmax.x < 0.0 || pmax.y < 0.0 || pmin.x >= float(pc.width) || pmin.y >= float(pc.height)) return false;
  // Clamped to the screen: what lies outside it cannot be seen, so only the part inside counts.
  ivec2 p0 = ivec2(floor(max(pmin, vec2(0.0))));
  ivec2 p1 = min(ivec2(floor(pmax)), ivec2(pc.width - 1u, pc.height - 1u));
  // The finest level at which the rectangle touches at most kTexels × kTexels texels. Greene's
  // classic choice is 2 × 2; this test runs once per seed triangle (not per pixel), so it can
  // afford up to 64 reads for a footprint 4 × tighter — which is what decides near the horizon,
  // where a coarse texel over a ridge's crest also holds the sky (farthest depth: no culling).
  const uint kTexels = 8u;
  uint l = 0u;
  uvec2 t0 = uvec2(p0) >> 1u, t1 = uvec2(p1) >> 1u;
  while ((t1.x - t0.x >= kTexels || t1.y - t0.y >= kTexels) && l + 1u < pc.levels) {
    ++l;
    t0 = uvec2(p0) >> (l + 1u);
    t1 = uvec2(p1) >> (l + 1u);
  }
  uint w = levelW(l), base = levelOffset(l);
  float farthest = 1.0;
  for (uint y = t0.y; y <= t1.y; ++y)
    for (uint x = t0.x; x <= t1.x; ++x) farthest = min(farthest, hiz[base + y * w + x]);
  // Strictly behind: a plant fragment at the same depth could still pass the depth test.
  return nearest < farthest;
}

// Metres of 2.5 pixels at distance d: thin things are drawn at least 1.5 pixels wide (grass,
// gravel, flower heads: up to ~2.1 pixels from their axis; plant_geometry.glsl metresPerPixel).
float pixelMargin(float d) {
  mat4 m = frame.viewProj;
  float focal = 0.5 * frame.viewport.y * length(vec3(m[0][1], m[1][1], m[2][1]));
  return 2.5 * d / focal;
}

// Where the plants of reach `reach` on t can put anything on screen: box 1 holds the plants
// themselves, box 2 their planar shadows (`shadow` 1; 0: no shadows are drawn; −1: a degenerate
// triangle, whose plants' shadows nothing bounds).
struct PlantBoxes {
  vec3 lo1, hi1, lo2, hi2;
  int shadow;
};

PlantBoxes plantBoxes(SeedTriangle t, float reach) {
  PlantBoxes b;
  vec3 lo = min(t.v0.xyz, min(t.v1.xyz, t.v2.xyz)), hi = max(t.v0.xyz, max(t.v1.xyz, t.v2.xyz));
  float far = sqrt(max(dot(t.v0.xyz, t.v0.xyz), max(dot(t.v1.xyz, t.v1.xyz), dot(t.v2.xyz, t.v2.xyz))));
  float r = reach + pixelMargin(far + 2.0 * reach);
  // Box 1: the plants (+ 0.05 m float slack).
  b.lo1 = lo - (r + 0.05);
  b.hi1 = hi + (r + 0.05);
  b.shadow = 0;
  if (pc.shadows == 0u) return b;
  // Box 2: the shadows. Each plant point is root + o with |o_i| ≤ r; its shadow is root + P o
  // + 0.015 n, P = I − l nᵀ / (n·l) the projection along the sunlight onto the triangle's plane
  // (the same for −n), so per axis |(P o)_i| ≤ r · Σ_j |P_ij|: on flat ground P's z row is 0.
  vec3 n = cross(t.v1.xyz - t.v0.xyz, t.v2.xyz - t.v0.xyz);
  float len = length(n);
  if (len == 0.0) {  // degenerate: no plane to reason about
    b.shadow = -1;
    return b;
  }
  n /= len;
  vec3 l = frame.sunDirection.xyz;
  float nl = dot(n, l);
  // plant_geometry.glsl draws shadows only where n·l > 0.05: below 0.04 there are none.
  if (abs(nl) <= 0.04) return b;
  vec3 q = l / nl, e;
  for (int i = 0; i < 3; ++i) {
    float row = 0.0;
    for (int j = 0; j < 3; ++j) row += abs((i == j ? 1.0 : 0.0) - q[i] * n[j]);
    e[i] = r * row + 0.015 * abs(n[i]) + 0.05;
  }
  b.lo2 = lo - e;
  b.hi2 = hi + e;
  b.shadow = 1;
  return b;
}

// True when every plant of reach `reach` on t, and its shadow, is certainly hidden.
bool hidden(SeedTriangle t, float reach) {
  PlantBoxes b = plantBoxes(t, reach);
  if (!boxHidden(b.lo1, b.hi1)) return false;
  return b.shadow == 0 || (b.shadow == 1 && boxHidden(b.lo2, b.hi2));
}

// Where the plants that may show (`plants`: species bits) are drawn, so the terrain's depth is
// written there before them (render/terrain_depth_handover.h): the boxes of the largest reach.
void markPlants(SeedTriangle t, uint plants) {
  float reach = 0.0;
  for (uint s = 0u; s < pc.species; ++s)
    if ((plants & (1u << s)) != 0u) reach = max(reach, pc.reach[s]);
  PlantBoxes b = plantBoxes(t, reach);
  markBox(b.lo1, b.hi1);
  if (b.shadow == 1) markBox(b.lo2, b.hi2);
  if (b.shadow == -1) markEverything();
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  SeedTriangle t = triangles[i];
  float n = t.v0.w;
  uint clusters = t.layer < 0 ? 0u : clusterCount(n, pc.clusterSize);
  if (clusters == 0u) {  // nothing to classify: not tested
    visible[i] = 0xffffffffu;
    return;
  }
  atomicAdd(tested, 1u);
  // One test per distinct reach (species share them: gravel and grass differ, two grasses may not).
  uint mask = 0xffffffffu, plants = 0u;
  for (uint s = 0u; s < pc.species; ++s) {
    float reach = pc.reach[s];
    if (reach < 0.0) continue;  // bare soil: rejected by classify anyway
    bool h = false, done = false;
    for (uint k = 0u; k < s; ++k)
      if (pc.reach[k] == reach) {
        h = ((mask >> k) & 1u) == 0u;
        done = true;
        break;
      }
    if (!done) h = hidden(t, reach);
    if (h) mask &= ~(1u << s);
    else plants |= 1u << s;
  }
  if (plants != 0u) {  // some species may show: classify decides per group
    visible[i] = mask;
    if ((plants & pc.drawn) != 0u) markPlants(t, plants & pc.drawn);
    return;
  }
  visible[i] = 0u;
  atomicAdd(culled, 1u);
  uint seeds = uint(ceil(min(n, float(pc.clusterSize))));
  atomicAdd(clustersCulled, seeds + clusters - 1u);
  atomicAdd(plantsCulled, uint(ceil(n)));
}
