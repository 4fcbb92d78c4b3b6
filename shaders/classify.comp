#version 450
#extension GL_GOOGLE_include_directive : require
// The classify pass, core seed ../shared/seeds/001_3eca9f2c7752e4fb.txt §3.5 in compute form:
// one thread per (seed triangle, work item: a seed of cluster 0 or a further cluster) of a bin (§3.2, eq. 15; vegetation/plant_bins.h),
// which expands the cluster, samples the base colour at its centre (cluster 0: at each seed),
// scores and picks the species (eq. 16–18), rejects bare soil and appends the group to its
// species' buffer. The CPU reference is vegetation/plant_seeding.cpp: same operations.
layout(local_size_x = 64) in;

#include "philox.glsl"
#include "colour_score.glsl"
#include "colour_calibration.glsl"
#include "classify_layout.glsl"

layout(set = 0, binding = 0, std140) uniform SpeciesBlock {
  Species species[kMaxSpecies];
  uvec4 speciesCount;
  vec4 calibration[3];  // the dataset's colour calibration (colour_calibration.glsl): rows of M, w offset
  // The species each landcover class code allows (code c: [c / 4][c % 4]; scene/landcover_masks.h),
  // read when pc.companions has bit 1.
  uvec4 landcoverMasks[64];
} catalog;
layout(set = 0, binding = 1, std430) readonly buffer Triangles { SeedTriangle triangles[]; };
layout(set = 0, binding = 2, std430) readonly buffer Order { uint order[]; };
// culledGroups / culledPlants: groups dropped because their species is hidden on their triangle.
layout(set = 0, binding = 3, std430) buffer Counters {
  uint groups[kMaxSpecies];
  uint plants[kMaxSpecies];
  uint culledGroups, culledPlants;
  uint wanted[kMaxSpecies];  // groups before the overflow thinning (vegetation/overflow_thinning.h)
};
layout(set = 0, binding = 4, std430) writeonly buffer Records { PlantCluster records[]; };
layout(set = 0, binding = 5) uniform sampler2DArray imagery;
// Per seed triangle, bit s set when species s's plants on it may show, 0 when none can (the Hi-Z
// occlusion test, hiz_cull.comp); read only when pc.cull is 1.
layout(set = 0, binding = 6, std430) readonly buffer Visible { uint visible[]; };
// Each imagery layer's companions (RG8 UNORM, render/terrain_pass.h): R the NDVI byte of
// datasets/tile_codec.h (0 = none), read when pc.companions has bit 0 (a near-infrared layer);
// G the landcover class code / 255 (0 = no class), read when it has bit 1 (a landcover layer).
layout(set = 0, binding = 7) uniform sampler2DArray companionLayers;
// The crowns near the camera (vegetation/canopy_cells.h): a toroidal table of the tree grid's
// cells about the camera's, each the tree of one cell (its centre relative to the camera, its
// crown radius, which cell it is).
struct CanopyEntry {
  float x, y, radiusM;
  uint cell;
};
layout(set = 0, binding = 8, std430) readonly buffer Canopy {
  vec2 canopyOffset;  // the camera's position in its cell
  float canopyCellM;
  uint canopyEnabled;
  ivec2 canopyCell;  // the camera's cell
  uvec2 canopyPad;
  CanopyEntry canopy[];
};

layout(push_constant) uniform Push {
  uint orderFirst;     // this bin's first entry in order[]
  uint triangleCount;  // triangles in the bin
  uint capacity;       // cluster slots per triangle
  uint clusterSize;    // C
  uint threadBase;     // for bins split over several dispatches
  uint speciesCapacity;
  uint cull;           // 1: skip triangles with visible[t] == 0
  uint hardFades;      // 1: a group is drawn whole or not at all (the fades off, for comparison)
  uint companions;     // bit 0: companionLayers holds NDVI, bit 1: landcover classes
  vec4 thinning[4];    // per species, the overflow thinning's pressure (0: keep every group)
} pc;

#include "species_choice.glsl"
#include "seeding.glsl"

// The imagery is bound as UNORM (sRGB bytes, not decoded by the texture unit, whose sRGB
// decoding is approximate on some devices): decoded here with the CPU's formula.
vec3 texelLinear(ivec2 p, int layer) {
  vec3 c = texelFetch(imagery, ivec3(p, layer), 0).rgb;
  return vec3(srgbDecode(c.r), srgbDecode(c.g), srgbDecode(c.b));
}

// Bilinear in linear light over texel centres, clamped to the edge: vegetation/imagery_texels.cpp.
vec3 imageryLinear(int layer, vec2 uv) {
  const float n = 256.0;
  float x = uv.x * n - 0.5, y = uv.y * n - 0.5;
  float fx0 = floor(x), fy0 = floor(y);
  int x0 = int(fx0), y0 = int(fy0);
  float fx = x - fx0, fy = y - fy0;
  ivec2 lo = clamp(ivec2(x0, y0), ivec2(0), ivec2(255)), hi = clamp(ivec2(x0 + 1, y0 + 1), ivec2(0), ivec2(255));
  vec3 a = texelLinear(lo, layer), b = texelLinear(ivec2(hi.x, lo.y), layer);
  vec3 c = texelLinear(ivec2(lo.x, hi.y), layer), d = texelLinear(hi, layer);
  return mix(mix(a, b, fx), mix(c, d, fx), fy);
}

// vegetation::sampleImageryNdvi: bilinear over the same texels, those without NDVI dropped.
float imageryNdvi(int layer, vec2 uv) {
  if ((pc.companions & 1u) == 0u) return kNoNdvi;
  const float n = 256.0;
  float x = uv.x * n - 0.5, y = uv.y * n - 0.5;
  float fx0 = floor(x), fy0 = floor(y);
  int x0 = int(fx0), y0 = int(fy0);
  float fx = x - fx0, fy = y - fy0;
  float sum = 0.0, weight = 0.0;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      ivec2 p = clamp(ivec2(x0 + i, y0 + j), ivec2(0), ivec2(255));
      float v = ndviOfTexel(texelFetch(companionLayers, ivec3(p, layer), 0).r);
      if (v == kNoNdvi) continue;
      float w = (i == 1 ? fx : 1.0 - fx) * (j == 1 ? fy : 1.0 - fy);
      sum += w * v;
      weight += w;
    }
  return weight > 0.0 ? sum / weight : kNoNdvi;
}

// The species the landcover class at uv allows: the texel whose square holds the point (classes
// are never blended; scene/plants_in_box.cpp alike); every species without a landcover layer.
uint landcoverAllowed(int layer, vec2 uv) {
  if ((pc.companions & 2u) == 0u) return 0xffffffffu;
  ivec2 p = clamp(ivec2(floor(uv * 256.0)), ivec2(0), ivec2(255));
  uint code = uint(round(texelFetch(companionLayers, ivec3(p, layer), 0).g * 255.0));
  return catalog.landcoverMasks[code >> 2u][code & 3u];
}

// The calibrated base colour under r: HSV and ExG (calibratedGround), the NDVI and the species
// the landcover class allows.
struct Ground {
  vec4 colour;
  float ndvi;
  uint allowed;
};
Ground baseGround(vec4 uv01, vec2 uv2, int layer, vec2 r) {
  vec2 uv0 = uv01.xy;
  vec2 uv = uv0 + r.x * (uv01.zw - uv0) + r.y * (uv2 - uv0);
  return Ground(calibratedGround(catalog.calibration, imageryLinear(layer, uv)), imageryNdvi(layer, uv),
                landcoverAllowed(layer, uv));
}

// vegetation::speciesPlantCount and speciesHorizonFade: the fade of a group of species `sp`,
// from the species' own count on the triangle and the size factor at its horizon.
float speciesFade(Species sp, SeedTriangle t, uint cluster, uint seed) {
  float n = min(t.v0.w, min(t.lodCount, sp.ground.x * t.areaM2));
  float h = sp.ground.y;
  float f = clamp((t.nearestM - 0.75 * h) / (0.25 * h), 0.0, 1.0);
  return plantFade(n, pc.clusterSize, cluster, seed) * (1.0 - f * f * (3.0 - 2.0 * f));
}

// vegetation::canopyCover: the same float operations in the same order.
const uint kCanopyCells = 90u;  // vegetation::kCanopyCells
const float kCanopyThinning = 0.85;
const float kCanopyEdge = 0.4;
uint canopyCellId(int cx, int cy) { return (uint(cx) & 0xFFFFu) | (uint(cy) << 16); }
float canopyCover(vec2 p) {
  if (canopyEnabled == 0u) return 0.0;
  precise float fx = (p.x + canopyOffset.x) / canopyCellM, fy = (p.y + canopyOffset.y) / canopyCellM;
  int cx = canopyCell.x + int(floor(fx));
  int cy = canopyCell.y + int(floor(fy));
  float cover = 0.0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      int x = cx + dx, y = cy + dy;
      CanopyEntry e = canopy[(uint(y) % kCanopyCells) * kCanopyCells + uint(x) % kCanopyCells];
      if (e.cell != canopyCellId(x, y)) continue;
      precise float ex = p.x - e.x, ey = p.y - e.y;
      precise float d = sqrt(ex * ex + ey * ey);
      precise float t = clamp((e.radiusM - d) / (kCanopyEdge * e.radiusM), 0.0, 1.0);
      cover = max(cover, t * t * (3.0 - 2.0 * t));
    }
  return cover;
}

// vegetation::thinningFade.
const float kThinningBand = 0.25;
float thinningFade(float pressure, float priority) {
  float edge = (1.0 + kThinningBand) * (1.0 - pressure);
  return clamp((edge - priority) / kThinningBand, 0.0, 1.0);
}

void append(uint tri, uint cluster, uint firstSeed, uint seedCount, ivec2 pick, float sPrime, float fade) {
  uint s = uint(pick.x);
  if (pc.cull != 0u && ((visible[tri] >> s) & 1u) == 0u) {  // this species is hidden here
    atomicAdd(culledGroups, 1u);
    atomicAdd(culledPlants, seedCount);
    return;
  }
  uint i = atomicAdd(groups[s], 1u);
  atomicAdd(plants[s], seedCount);
  if (i >= pc.speciesCapacity) return;  // counted: the figures report the overflow
  records[s * pc.speciesCapacity + i] = PlantCluster(tri, cluster, firstSeed, seedCount, s, sPrime, fade, 0u);
}

// Appends group (cluster, firstSeed, seedCount) as species pick.x with weight w on its fade;
// nothing for bare soil or a fade of 0 (beyond its species' own count, or weight 0).
void appendPick(uint tri, SeedTriangle t, uint cluster, uint firstSeed, uint seedCount, vec2 pick, float w) {
  if (pick.x < 0.0) return;
  float fade = speciesFade(catalog.species[int(pick.x)], t, cluster, firstSeed) * w;
  if (fade <= 0.0) return;
  // Wanted, then thinned by its priority when the species' buffer is under pressure; the
  // wanted count sets the next frames' pressure (ClassifyPass::updateThinning).
  uint s = uint(pick.x);
  atomicAdd(wanted[s], 1u);
  fade *= thinningFade(pc.thinning[s / 4u][s % 4u], groupPriority(uvec2(t.keyLo, t.keyHi), cluster, firstSeed));
  if (fade <= 0.0) return;
  if (pc.hardFades != 0u) fade = 1.0;
  append(tri, cluster, firstSeed, seedCount, ivec2(pick.x, 0), pick.y, fade);
}

// The species of a group at r (eq. 16–18, z its draw): from the imagery drawn now, and while
// that changes from the imagery before it too — the same species keeps its plants (s′ moving
// between the two), different ones cross-fade by size (vegetation::classifyTriangle).
void classifyGroup(uint tri, SeedTriangle t, uint cluster, uint firstSeed, uint seedCount, vec2 r, float z) {
  if (canopyEnabled != 0u) {  // under a crown the group thins out (vegetation/canopy_cells.h)
    precise vec3 p = t.v0.xyz + r.x * (t.v1.xyz - t.v0.xyz) + r.y * (t.v2.xyz - t.v0.xyz);
    float cover = canopyCover(p.xy);
    if (cover > 0.0 &&
        philoxU01(philoxDraw(uvec2(t.keyLo, t.keyHi), cluster, kSlotCanopy + firstSeed).x) < kCanopyThinning * cover)
      return;
  }
  Ground now = baseGround(t.uv01, t.uv2, t.layer, r);
  vec2 pick = choosePlantSpecies(now.colour, now.ndvi, z, now.allowed);
  float w = t.imageryBlend;
  if (t.previousLayer >= 0 && w < 1.0) {
    Ground then = baseGround(t.previousUv01, t.previousUv2, t.previousLayer, r);
    vec2 before = choosePlantSpecies(then.colour, then.ndvi, z, then.allowed);
    if (before.x == pick.x) {
      pick.y = mix(before.y, pick.y, w);
      w = 1.0;
    } else {
      appendPick(tri, t, cluster, firstSeed, seedCount, before, 1.0 - w);
    }
  }
  appendPick(tri, t, cluster, firstSeed, seedCount, pick, w);
}

void main() {
  uint id = pc.threadBase + gl_GlobalInvocationID.x;
  if (id >= pc.triangleCount * pc.capacity) return;
  uint tri = order[pc.orderFirst + id / pc.capacity];
  uint item = id % pc.capacity;
  if (pc.cull != 0u && visible[tri] == 0u) return;  // hidden behind the terrain: never expanded
  SeedTriangle t = triangles[tri];
  float n = t.v0.w;
  if (t.layer < 0) return;
  uint clusters = clusterCount(n, pc.clusterSize);
  if (clusters == 0u) return;
  // Items: the seeds of cluster 0 (each its own species), then clusters 1, 2, … (plant_seeding.h).
  uint seeds = uint(ceil(min(n, float(pc.clusterSize))));
  if (item >= seeds + clusters - 1u) return;
  uvec2 key = uvec2(t.keyLo, t.keyHi);
  if (item < seeds) {
    float z = philoxU01(philoxDraw(key, 0u, kSlotColourSpecies + item).y);
    classifyGroup(tri, t, 0u, item, 1u, seedPoint(key, 0u, item), z);
    return;
  }
  uint c = item - seeds + 1u;
  float z = philoxU01(philoxDraw(key, c, kSlotSpecies).x);
  classifyGroup(tri, t, c, 0u, pc.clusterSize, clusterCentre(key, c), z);
}
