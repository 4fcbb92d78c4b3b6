#version 460
#extension GL_GOOGLE_include_directive : require
// The trees cast into a sun shadow cascade, rasterised in compute (render/sun_shadow_pass.h,
// render/tree_pass.h): every caster the classify listed for the cascade (tree_classify.comp) as
// its impostor's triangle turned to the sun (common/tree_impostor_frame.glsl), the nearest
// captured view's silhouette over it. The H100 and H200 have few graphics units: the same
// triangles drawn as depth-only fragments took 0.4 ms for the nearest cascade and 0.9 ms for the
// farthest over the Kolob forest, most of the shadow pass's 1.3 ms in the slowest frames.
//
// One workgroup per caster at a time (the casters of every model in one sequence), a thread per
// texel of an 8 × 8 block, the blocks of the triangle's box in turn; the dispatch's z groups take turns over a caster's blocks, so the
// nearest cascade's large casters (hundreds of blocks each) are shared by several groups. A texel whose centre lies in the triangle (edges included), within the
// depth range, inside the rectangle the model fills and kept by the cross-fade's dither is
// covered when the atlas's coverage over its footprint says so (below); it keeps the nearest
// depth to the sun (reverse-Z: the largest, as uint bits: non-negative floats order as their
// bits) through an atomic max, so the map is the same whatever order the casters come in. The
// depth carries the bias the graphics pipeline had (constant −1 unit of the primitive's exponent,
// slope −1.5: Vulkan's depth-bias rule for float depth), away from the sun.
//
// The alpha test is a supersampled (4 rotated-grid taps) conservative coverage test over the
// texel's footprint (alpha-tested geometry thins and breaks up under minification: Wyman &
// McGuire, "Hashed Alpha Testing", I3D 2017; no hash here, the map must stay deterministic frame
// to frame). The atlas has no mip levels and its texels are finer than a cascade's (0.16 m against
// 0.1–1.4 m): one bilinear read per shadow texel point-sampled the needles and the trunk, so a
// thin tree's shadow came out as dashes and a sparse crown's as a thinned-out scatter (issue 39
// item 8, render/README.md). Four reads across the footprint (the uv's gradient per texel), each a
// bilinear 2 × 2, see every atlas texel under a footprint of up to about 4 × 4 (the nearer two
// cascades); in the farthest (1.4 m, about 9 × 9) they see a sample of it. The texel is kept when
// any of them sees coverage: a hard map cannot hold a partial shadow, and the receivers' PCF
// softens a one-texel line into a half one.
//
// Push constants (common/tree_push.glsl): capture = the cascade's matrix, lod = the cascade.
#include "common/frame_uniforms.glsl"
#include "common/simulation_block.glsl"
#include "simulation/shared/tree_bending.glsl"
#include "common/tree_layout.glsl"
#include "common/tree_push.glsl"
#include "common/tree_impostor.glsl"
#include "common/tree_impostor_frame.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 1, binding = 6, std430) readonly buffer ImpostorDraws { uint impostorDraws[]; };
layout(set = 1, binding = 8) uniform sampler2DArray impostorAlbedo;
layout(set = 2, binding = 0, r32ui) uniform uimage2DArray shadowTarget;

const float kTreeShadowCoverage = 0.02;  // of the footprint: any tap that sees the crown keeps it
const float kBiasConstant = -1.0, kBiasSlope = -1.5;

float footprintCoverage(vec2 uv, vec2 dx, vec2 dy, float layer) {
  float a = 0.0;
  const vec2 grid[4] = vec2[](vec2(-0.125, -0.375), vec2(0.375, -0.125), vec2(0.125, 0.375), vec2(-0.375, 0.125));
  for (int i = 0; i < 4; ++i) a += textureLod(impostorAlbedo, vec3(uv + grid[i].x * dx + grid[i].y * dy, layer), 0.0).a;
  return 0.25 * a;
}

// The caster's triangle: per corner its texel position (x, y) and depth (z), its atlas uv.
shared vec3 sCorner[3];
shared vec2 sUv[3];
shared vec4 sRect;
// Every model's casters in this cascade, one after the other: where each model's start.
shared uint sModelStart[kMaxTreeModels + 1u];

void main() {
  uint cascade = push.lod;
  uint models = min(trees.counts.y, kMaxTreeModels);
  uint lid = gl_LocalInvocationIndex;
  if (lid < models) {
    uint command = treeCasterCommand(cascade, lid) * 5u;
    sModelStart[lid + 1u] = min(impostorDraws[command + 1u], treeCasterCapacity(cascade));
  }
  barrier();
  if (lid == 0u) {
    sModelStart[0] = 0u;
    for (uint k = 1u; k <= models; ++k) sModelStart[k] += sModelStart[k - 1u];
  }
  barrier();
  uint total = sModelStart[models];
  float size = float(imageSize(shadowTarget).x);
  // The groups take the casters in turns, whichever model they belong to (a forest's casters are
  // mostly one or two models').
  uint m = 0u;
  for (uint i = gl_WorkGroupID.x; i < total; i += gl_NumWorkGroups.x) {
    while (i >= sModelStart[m + 1u]) ++m;  // i only grows
    TreeModelGpu model = trees.models[m];
    uvec4 entry = treeVisible[impostorDraws[treeCasterCommand(cascade, m) * 5u + 4u] + i - sModelStart[m]];
    TreeInstanceGpu t = treeInstances[entry.x];
    if (lid < 3u) {
      TreeImpostorFrame f = treeImpostorFrame(entry, t, model, true);
      vec2 uv;
      vec3 rel = treeImpostorCorner(f, t, model, lid, uv);
      vec4 s = push.capture * vec4(rel, 1.0);  // orthographic: w = 1
      sCorner[lid] = vec3((s.xy * 0.5 + 0.5) * size, s.z);
      sUv[lid] = uv;
      if (lid == 0u) sRect = treeImpostorRect(f, model);
    }
    barrier();
    vec3 a = sCorner[0], b = sCorner[1], c = sCorner[2];
    vec2 ua = sUv[0], ub = sUv[1], uc = sUv[2];
    vec4 rect = sRect;
    float layer = float(model.mesh1.w);
    barrier();  // the next caster may overwrite the corners
    float area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    if (abs(area) < 1e-12) continue;
    // Texel centres (x + ½, y + ½) the triangle's box holds, within the map.
    ivec2 lo = ivec2(max(ceil(min(a.xy, min(b.xy, c.xy)) - 0.5), vec2(0.0)));
    ivec2 hi = ivec2(min(floor(max(a.xy, max(b.xy, c.xy)) - 0.5), vec2(size - 1.0)));
    if (any(greaterThan(lo, hi))) continue;
    // Barycentric gradients per texel: depth and uv are affine in an orthographic view.
    vec2 gb = vec2(c.y - a.y, a.x - c.x) / area, gc = vec2(a.y - b.y, b.x - a.x) / area;
    vec2 dz = gb * (b.z - a.z) + gc * (c.z - a.z);
    vec2 uvDx = gb.x * (ub - ua) + gc.x * (uc - ua), uvDy = gb.y * (ub - ua) + gc.y * (uc - ua);
    float maxZ = max(abs(a.z), max(abs(b.z), abs(c.z)));
    float unit = maxZ > 0.0 ? exp2(floor(log2(maxZ)) - 23.0) : 0.0;
    float bias = kBiasSlope * max(abs(dz.x), abs(dz.y)) + kBiasConstant * unit;
    float threshold = uintBitsToFloat(entry.y);
    // The box's 8 × 8 blocks, shared out among the dispatch's layers of groups (z).
    uint across = uint(hi.x - lo.x) / 8u + 1u, blocks = across * (uint(hi.y - lo.y) / 8u + 1u);
    for (uint j = gl_WorkGroupID.z; j < blocks; j += gl_NumWorkGroups.z) {
      ivec2 px = lo + 8 * ivec2(j % across, j / across) + ivec2(gl_LocalInvocationID.xy);
      if (px.x > hi.x || px.y > hi.y) continue;
      vec2 p = vec2(px) + 0.5;
      float wb = dot(p - a.xy, gb), wc = dot(p - a.xy, gc), wa = 1.0 - wb - wc;
      if (min(wa, min(wb, wc)) < 0.0) continue;
      float z = a.z + wb * (b.z - a.z) + wc * (c.z - a.z);
      if (z < 0.0 || z > 1.0) continue;  // outside the cascade's depth range: clipped
      vec2 uv = ua + wb * (ub - ua) + wc * (uc - ua);
      if (any(greaterThan(abs(uv - rect.xy), rect.zw))) continue;
      if (!treeKeepsPixel(threshold, treeDither(p, entry.x))) continue;
      if (footprintCoverage(uv, uvDx, uvDy, layer) < kTreeShadowCoverage) continue;
      float depth = clamp(z + bias, 0.0, 1.0);
      imageAtomicMax(shadowTarget, ivec3(px, int(cascade)), floatBitsToUint(depth));
    }
  }
}
