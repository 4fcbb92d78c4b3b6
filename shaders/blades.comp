#version 450
#extension GL_GOOGLE_include_directive : require
// The compute blade path (render/blade_pass.h; core seed 001_3eca9f2c7752e4fb.txt §2.3–2.4,
// §3.5–3.6): everything the tessellation path recomputes per vertex (plant.tese) or per
// primitive (grass.geom, gravel.geom, flowers.geom) is computed here once per plant, and the
// plant is written out as finished triangles that blade.vert only has to fetch. One thread per
// classified group of species pc.species for the group's frustum test and eq. 4 segment count
// (common/plant_lod.glsl), then the workgroup's plants shared out one per thread: per plant its
// parameters (common/plant_params.glsl), the imagery colour under it, its vertices on the solved
// blade shape, lit per vertex (common/plant_lighting.glsl), the kind's extrusion (tapered blade
// strip, camera-facing stone diamond, stem with a flower head) and, when shadows are on and the
// sun is high enough over the seed triangle, the same geometry projected onto the triangle's
// plane (§3.6). The same plants, segments and triangles
// as the tessellation path; the figures (blade_args.comp) count them.
//
// Space is reserved per workgroup (a prefix sum and shared-memory atomics, then one global atomic
// per counter), so the global counters see 3 atomics per 64 groups. A plant that does not fit in
// the buffers is dropped whole and counted; indices it reserved below the capacity become
// degenerate triangles.
layout(local_size_x = 64) in;
#include "frame_uniforms.glsl"
#include "philox.glsl"
#include "seeding.glsl"
#include "classify_layout.glsl"
#include "plant_common.glsl"
#include "plant_lod.glsl"
#include "plant_shape.glsl"
#include "blade_layout.glsl"
#include "atmosphere.glsl"
#include "plant_lighting.glsl"

// Classify's indirect draws (instanceCount: the species' groups, already clamped to its buffer).
layout(set = 2, binding = 4, std430) readonly buffer ClassifyDraws { uvec4 classifyDraws[kMaxSpecies]; };

const uint kGrass = 0u, kGravel = 1u, kFlowers = 2u;

const uint kGroupSize = 64u;  // render/blade_pass.cpp and blade_args.comp: one thread per group
shared uint sPlantEnd[kGroupSize];   // inclusive prefix sum of the groups' plants in view
shared uint sVertexAt[kGroupSize];   // each group's first vertex and index in the workgroup's space
shared uint sIndexAt[kGroupSize];
shared uint sShape[kGroupSize];      // segments n | copies << 8 | kind << 10
shared uint sVertices, sIndices;
shared uint sBaseVertex, sBaseIndex, sBasePlant;

// Vertices and indices one copy (the plant or its shadow) of a plant of `kind` with `n`
// segments needs.
uvec2 plantSize(uint kind, uint n) {
  if (kind == kGravel) return uvec2(4u, 6u);
  uvec2 strip = uvec2(2u * (n + 1u), 6u * n);
  return kind == kFlowers ? strip + uvec2(4u, 6u) : strip;
}

uint gKind, gPlantWord;
float gGrown;  // groupLod's z: how far the blade's last segment has grown in
vec4 gPlane;
vec4 gGroundMod;  // the imagery colour under the root (rgb) and the plant's colour modulation (a)
uint gVertex;  // next vertex to write
float gPressed;  // PlantParams::pressed: lit as the canopy's top

void putVertex(vec3 p, vec3 n, vec2 blade, bool shadow) {
  BladeVertex v;
  v.pos = shadow ? shadowPoint(p, gPlane) : p;
  // A shadow's colour is black: its red channel carries the shadow's coverage instead.
  vec3 c = shadow ? vec3(shadowStrength(p), 0.0, 0.0)
                  : plantColour(p, n, vec2(blade.x, max(blade.y, gPressed)), gGroundMod.rgb, gGroundMod.a,
                                (gPlantWord >> kBladeKindShift) & 3u, gPlane.xyz);
  v.colour = uvec2(packHalf2x16(c.rg), packHalf2x16(vec2(c.b, 0.0)));
  v.plant = gPlantWord | (shadow ? kBladeShadowBit : 0u);
  v.blade = packSnorm2x16(blade);
  v.species = pc.species;
  bladeVertices[gVertex++] = v;
}

// Quads q = first … first + count − 1 of the strip starting at vertex `base`: vertices 2q, 2q + 1,
// 2q + 2, 2q + 3 — the two triangles a geometry shader's 4-vertex strip makes.
uint putStripIndices(uint at, uint base, uint quads) {
  for (uint q = 0u; q < quads; ++q) {
    uint v = base + 2u * q;
    bladeIndices[at++] = v;
    bladeIndices[at++] = v + 1u;
    bladeIndices[at++] = v + 2u;
    bladeIndices[at++] = v + 1u;
    bladeIndices[at++] = v + 2u;
    bladeIndices[at++] = v + 3u;
  }
  return at;
}

// One copy of the plant (shadow: projected onto the seed triangle's plane) at vertex gVertex and
// index `at`; returns the next index.
uint putPlant(PlantParams p, uint n, bool shadow, uint at) {
  uint base = gVertex;
  if (gKind == kGravel) {  // as gravel.geom: a diamond facing the camera, its foot on the ground
    vec3 root = p.root;
    float px = 1.5 * metresPerPixel(length(root));
    float size = max(max(p.width, p.height), px);
    vec3 view = normalize(root);
    vec3 groundN = gPlane.xyz;
    vec3 right = cross(view, groundN);
    right = length(right) > 1e-3 ? normalize(right) : vec3(-sin(p.orientation), cos(p.orientation), 0.0);
    vec3 up = normalize(cross(right, view));
    if (dot(up, groundN) < 0.0) up = -up;
    vec3 side = right * (0.5 * size), rise = up * (0.4 * size);
    vec3 nrm = normalize(-view + groundN);
    vec3 c = root + rise;
    putVertex(c - side, nrm, vec2(-1.0, 0.5), shadow);
    putVertex(c - rise, nrm, vec2(0.0, 0.0), shadow);
    putVertex(c + rise, nrm, vec2(0.0, 1.0), shadow);
    putVertex(c + side, nrm, vec2(1.0, 0.5), shadow);
    return putStripIndices(at, base, 1u);
  }
  // Grass blades (grass.geom) and flower stems (flowers.geom): a strip of n quads.
  BladeVertexFrame tip;
  for (uint j = 0u; j <= n; ++j) {
    BladeVertexFrame f = morphedBladeFrame(p, j, n, gGrown);
    float x = f.along;
    float halfWidth;
    if (gKind == kGrass)  // never thinner than 1.5 pixels, tapering to the tip
      halfWidth = 0.5 * max(p.width, 1.5 * metresPerPixel(length(f.pos))) * pow(1.0 - x, 0.7);
    else
      halfWidth = 0.5 * max(0.5 * p.width, metresPerPixel(length(f.pos)));
    putVertex(f.pos - f.side * halfWidth, f.normal, vec2(-1.0, x), shadow);
    putVertex(f.pos + f.side * halfWidth, f.normal, vec2(1.0, x), shadow);
    tip = f;
  }
  at = putStripIndices(at, base, n);
  if (gKind != kFlowers) return at;
  // The head: a square lying across the stem's tip, a few widths across (kind 2).
  uint stemWord = gPlantWord;
  gPlantWord = (gPlantWord & ~(3u << kBladeKindShift)) | (2u << kBladeKindShift);
  float r = max(2.5 * p.width, 1.5 * metresPerPixel(length(tip.pos)));
  vec3 a = tip.side * r, b = cross(vec3(0.0, 0.0, 1.0), tip.side) * r;
  vec3 up = vec3(0.0, 0.0, 1.0);
  uint head = gVertex;
  putVertex(tip.pos - a - b, up, vec2(-1.0, 0.0), shadow);
  putVertex(tip.pos + a - b, up, vec2(1.0, 0.0), shadow);
  putVertex(tip.pos - a + b, up, vec2(-1.0, 1.0), shadow);
  putVertex(tip.pos + a + b, up, vec2(1.0, 1.0), shadow);
  gPlantWord = stemWord;
  return putStripIndices(at, head, 1u);
}

void main() {
  // Phase 1, one thread per group: the frustum test, eq. 4 segments, shadow copies, kind.
  uint lid = gl_LocalInvocationIndex;
  uint gi = gl_GlobalInvocationID.x;
  uint plants = 0u, n = 1u, copies = 1u, kind = 0u;
  if (gi < classifyDraws[pc.species].y) {
    PlantCluster g = records[pc.species * pc.speciesCapacity + gi];
    SeedTriangle t = triangles[g.triangle];
    vec3 lod = groupLod(g, t);
    n = uint(lod.y);
    kind = catalog.species[g.species].flags.y;
    vec3 nrm = normalize(cross(t.v1.xyz - t.v0.xyz, t.v2.xyz - t.v0.xyz));
    copies = ((pc.flags & kFlagShadows) != 0u && castsShadow(vec4(nrm, -dot(nrm, t.v0.xyz))) &&
              shadowsReach(shadowNearestM(g, t))) ? 2u : 1u;
    plants = lod.x > 0.5 ? g.seedCount : 0u;
  }
  uvec2 size = plantSize(kind, n) * copies;
  sShape[lid] = n | (copies << 8u) | (kind << 10u);

  // Reserve the workgroup's space: an ordered prefix sum of plants (phase 2 finds a plant's
  // group by it), shared atomics for vertices and indices, then one global atomic per counter.
  if (lid == 0u) {
    sVertices = 0u;
    sIndices = 0u;
  }
  sPlantEnd[lid] = plants;
  barrier();
  for (uint off = 1u; off < kGroupSize; off <<= 1u) {
    uint v = lid >= off ? sPlantEnd[lid - off] : 0u;
    barrier();
    sPlantEnd[lid] += v;
    barrier();
  }
  sVertexAt[lid] = atomicAdd(sVertices, plants * size.x);
  sIndexAt[lid] = atomicAdd(sIndices, plants * size.y);
  barrier();
  uint total = sPlantEnd[kGroupSize - 1u];
  if (lid == 0u) {
    sBaseVertex = atomicAdd(state.reservedVertices, sVertices);
    sBaseIndex = atomicAdd(state.reservedIndices, sIndices);
    sBasePlant = atomicAdd(state.reservedPlants, total);
  }
  barrier();

  // Phase 2, one thread per plant: the workgroup's plants shared out over its threads, so a
  // group of C plants is C threads' work, not one thread's loop.
  for (uint q = lid; q < total; q += kGroupSize) {
    uint k = 0u;  // the group: the first whose prefix end passes q
    for (uint step = kGroupSize / 2u; step > 0u; step >>= 1u)
      if (sPlantEnd[k + step - 1u] <= q) k += step;
    uint first = k == 0u ? 0u : sPlantEnd[k - 1u];
    uint l = q - first;
    uint shape = sShape[k];
    uint segs = shape & 0xffu, copiesK = (shape >> 8u) & 3u, kindK = shape >> 10u;
    uvec2 sz = plantSize(kindK, segs) * copiesK;
    uint vAt = sBaseVertex + sVertexAt[k] + l * sz.x;
    uint iAt = sBaseIndex + sIndexAt[k] + l * sz.y;
    uint pAt = sBasePlant + q;
    if (vAt + sz.x > state.vertexCapacity || iAt + sz.y > state.indexCapacity || pAt >= state.plantCapacity ||
        pAt > kBladePlantMask) {
      // Does not fit: dropped whole; its indices under the capacity draw nothing.
      atomicAdd(state.droppedPlants, 1u);
      for (uint i = iAt; i < min(iAt + sz.y, state.indexCapacity); ++i) bladeIndices[i] = 0u;
      continue;
    }
    PlantCluster g = records[pc.species * pc.speciesCapacity + gl_WorkGroupID.x * kGroupSize + k];
    SeedTriangle t = triangles[g.triangle];
    vec3 nrm = normalize(cross(t.v1.xyz - t.v0.xyz, t.v2.xyz - t.v0.xyz));
    gPlane = vec4(nrm, -dot(nrm, t.v0.xyz));
    uint seed = g.firstSeed + l;
    PlantParams p = plantParams(g, t, seed);
    plantMotion(p, kindK);
    gPressed = p.pressed;
    vec2 r = seedPoint(uvec2(t.keyLo, t.keyHi), g.cluster, seed);
    gGroundMod = vec4(groundColour(t, r), p.colourModulation);
    gKind = kindK;
    gGrown = groupLod(g, t).z;
    gPlantWord = pAt | ((kindK == kGravel ? 1u : 0u) << kBladeKindShift);
    gVertex = vAt;
    uint at = putPlant(p, segs, false, iAt);
    if (copiesK == 2u) putPlant(p, segs, true, at);
  }
}
