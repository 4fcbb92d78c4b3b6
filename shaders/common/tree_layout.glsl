#ifndef TREE_LAYOUT_GLSL
#define TREE_LAYOUT_GLSL
// The trees' GPU data (issue 20), set 1 of the tree pipelines: mirrors render/tree_layout.h and
// the private blocks of render/tree_pass.cpp (std140 / std430; static_asserts there).

const uint kTreePageSize = 256u;
const uint kMaxTreeModels = 32u;
const uint kTreeLodFull = 0u, kTreeLodReduced = 1u, kTreeLodImpostor = 2u;
const uint kTreeFlagFades = 1u;
const uint kTreeShadowCascades = 3u;
// The counters (render/tree_pass_internal.h): 0 instances, 1–3 appended per level, 4 dropped,
// 5–7 shadow casters per cascade.

struct TreeModelGpu {
  uvec4 mesh0;  // x: first index (full), y: index count (full), z: vertex offset (full), w: first branch
  uvec4 mesh1;  // x: first index (reduced), y: index count (reduced), z: vertex offset (reduced), w: atlas layer
  vec4 shape;   // x: model height (m), y: crown radius (m), z: impostor half extent (m), w: impostor centre height (m)
  vec4 leaf;    // rgb: leaf albedo (linear), w: translucency
  vec4 bark;    // rgb: bark albedo (linear), w: form (0 conifer, 1 broadleaf)
  // The impostor's triangle per quarter of sin(elevation) (render/tree_impostor_outline.h): apex
  // height and base half width, in the rectangle's units.
  vec4 triangleApex, triangleBase;
  uvec4 ids;    // x: the species (catalog index; the AOV frames' species, aov.glsl), y: crown area radius (m, float bits)
};

layout(set = 1, binding = 0, std140) uniform TreeBlock {
  vec4 camera;      // xyz: camera in the local ENU frame (float), w: unused
  vec4 lod;         // x: full model up to (tree heights), y: reduced up to (heights), z: horizon (m), w: fade share
  vec4 frustum[6];  // camera-relative planes: dot(xyz, p) + w ≥ 0 inside
  uvec4 counts;     // x: instance slots (pages × kTreePageSize), y: models, z: flags, w: impostor views per side
  uvec4 capacity;   // visible entries per model: x full, y reduced, z impostor
  vec4 limits;      // x: how far shadow casters may lie outside the view (m), y: impostors end (tree heights),
                    // z: the near fade (m, 0 off: treeNearKeep), w: unused
  uvec4 casters;    // xyz: shadow caster entries per model in each cascade, w: unused
  TreeModelGpu models[kMaxTreeModels];
} trees;

struct TreeInstanceGpu {
  vec3 position;  // local ENU (m)
  uint model;
  float heightM;
  float crownM;
  uint seed;
  uint colour;  // rgb: the imagery under the tree (sRGB bytes), a: colour factor (render/tree_layout.h)
};

// The model's scale for one tree, x horizontal and y vertical: the tree's height over the model's,
// and its crown width over the diameter of the model's crown area seen from above
// (vegetation/crown_projection.h), so the crown covers the disk the placement gave it. The
// horizontal scale stays within 0.6 … kTreeCrownStretch times the vertical one: a short tree with
// a wide crown is not flattened into a disk.
const float kTreeCrownStretch = 3.5, kTrunkStretch = 1.5;
vec2 treeScale(TreeInstanceGpu t, TreeModelGpu m) {
  float sz = t.heightM / m.shape.x;
  float sxy = clamp(t.crownM / (2.0 * uintBitsToFloat(m.ids.y)), 0.6 * sz, kTreeCrownStretch * sz);
  return vec2(sxy, sz);
}

struct TreeBranchGpu {
  vec4 originLength;  // xyz origin, w length L (m)
  vec4 tC2;           // xyz unit axis, w c2
  vec4 rC4;           // xyz r, w c4
  vec4 sFrequency;    // xyz s, w resonance (Hz)
  vec4 link;          // x: parent (int bits, −1 trunk), y: x on the parent, z: level (uint bits), w: compliance
};

layout(set = 1, binding = 1, std430) readonly buffer TreeInstances { TreeInstanceGpu treeInstances[]; };
// One entry per tree drawn at one level: x instance, y dither threshold (float bits: ≤ 1 keep the
// pixels whose dither is below it, > 1 keep those at or above it − 1), zw the wind at the tree (m/s).
layout(set = 1, binding = 2, std430) buffer TreeVisible { uvec4 treeVisible[]; };
layout(set = 1, binding = 3, std430) readonly buffer TreeBranches { TreeBranchGpu treeBranches[]; };

// The visible list's region of model m at level lod.
uint treeRegionBase(uint m, uint lod) {
  uint perModel = trees.capacity.x + trees.capacity.y + trees.capacity.z;
  uint base = m * perModel;
  if (lod >= 1u) base += trees.capacity.x;
  if (lod >= 2u) base += trees.capacity.y;
  return base;
}
uint treeRegionCapacity(uint lod) { return lod == 0u ? trees.capacity.x : (lod == 1u ? trees.capacity.y : trees.capacity.z); }
// Shadow casters of model m into cascade c: their region starts at their draw's firstInstance
// (render/tree_models.cpp lays the regions out, after every model's).
uint treeCasterCapacity(uint c) { return c == 0u ? trees.casters.x : (c == 1u ? trees.casters.y : trees.casters.z); }
// The impostor draws' commands (VkDrawIndexedIndirectCommand, 5 words): per model the impostors, then
// per cascade and model the shadow casters.
uint treeCasterCommand(uint c, uint m) { return trees.counts.y * (1u + c) + m; }

// The pixel's dither value for cross-fades: interleaved gradient noise (Jimenez 2014) shifted per
// tree, so two levels of one tree split the pixels exactly and neighbours do not share a pattern.
float treeDither(vec2 fragCoord, uint instance) {
  float ign = fract(52.9829189 * fract(dot(fragCoord, vec2(0.06711056, 0.00583715))));
  return fract(ign + float(instance & 1023u) * 0.61803399);
}
bool treeKeepsPixel(float threshold, float dither) {
  return threshold <= 1.0 ? dither < threshold : dither >= threshold - 1.0;
}

// The near fade (render/tree_layout.h TreeLodDistances::nearFadeM, trees.limits.z = F metres): a
// model's surface dissolves within F of the camera and is gone within F / 2, so a camera flying
// through a crown sees past the branches at its lens instead of a screen filled by a few cards
// (tree.vert shrinks the crowns' cores away as well). F = 0: off, the default (it costs frame time
// where it acts: render/tree_layout.h).
// The share of the surface kept at camera-relative point `rel` (0 … 1), compared with the dither
// (tree.frag, before the coverage: a fragment faded out writes neither colour nor depth). Not a
// clip distance: cutting the cards before rasterising (gl_ClipDistance) made kolob-forest's trees
// pass 2–3 ms slower in the frames with cards within the fade on an H100 — primitives clipped for
// real on the few graphics units (bench/README.md).
// treeNearShare: the same of a surface `distanceM` from the camera (tree.vert's cores use it too).
float treeNearShare(float distanceM) {
  float f = trees.limits.z;
  return f > 0.0 ? clamp((distanceM - 0.5 * f) / (0.5 * f), 0.0, 1.0) : 1.0;
}
float treeNearKeep(vec3 rel) { return treeNearShare(length(rel)); }

// The tree's yaw and lean from its seed (Philox words are uniform: any bits will do).
vec3 treeRotate(vec3 v, uint seed) {
  float yaw = float(seed & 0xffffu) * (6.28318530718 / 65536.0);
  float leanDir = float((seed >> 16) & 0xffu) * (6.28318530718 / 256.0);
  float lean = float((seed >> 24) & 0xffu) * (0.06 / 256.0);  // up to 3.4°
  float cy = cos(yaw), sy = sin(yaw);
  v = vec3(cy * v.x - sy * v.y, sy * v.x + cy * v.y, v.z);
  vec3 axis = vec3(-sin(leanDir), cos(leanDir), 0.0);
  float cl = cos(lean), sl = sin(lean);
  return v * cl + cross(axis, v) * sl + axis * dot(axis, v) * (1.0 - cl);
}
// treeRotate as a matrix, its six sines and cosines taken once: for a vertex stage that turns
// several vectors, and for a fragment stage that turns one per fragment (the matrix passed flat).
mat3 treeRotation(uint seed) {
  return mat3(treeRotate(vec3(1.0, 0.0, 0.0), seed), treeRotate(vec3(0.0, 1.0, 0.0), seed),
              treeRotate(vec3(0.0, 0.0, 1.0), seed));
}
vec3 treeUnrotateYaw(vec3 v, uint seed) {
  float yaw = float(seed & 0xffffu) * (6.28318530718 / 65536.0);
  float cy = cos(yaw), sy = sin(yaw);
  return vec3(cy * v.x + sy * v.y, -sy * v.x + cy * v.y, v.z);
}
#endif
