// What every plant pipeline's stages share (render/plant_pass.h): the classify pass's buffers,
// the species block, the blade-shape table, the imagery and the push constants, plus the
// per-plant parameters — drawn from the same Philox slots as vegetation/plant_seeding.cpp, so a
// plant on screen is the plant the CPU reference (and `vegstream plants`) describes.
// Include frame_uniforms.glsl, philox.glsl, seeding.glsl and classify_layout.glsl first.

layout(set = 1, binding = 0, std140) uniform SpeciesBlock {
  Species species[kMaxSpecies];
  uvec4 speciesCount;
} catalog;
layout(set = 1, binding = 1, std430) readonly buffer Triangles { SeedTriangle triangles[]; };
layout(set = 1, binding = 2, std430) readonly buffer Records { PlantCluster records[]; };
layout(set = 1, binding = 3) uniform sampler2D bladeTable;       // RGBA32F: x segment end, y stiffness row
layout(set = 1, binding = 4) uniform sampler2DArray imagery;     // sRGB tiles, sampled as linear colour

layout(push_constant) uniform PlantPush {
  uint species;
  uint speciesCapacity;
  uint maxSegments;      // n_max of eq. 4
  uint flags;            // bit 0: planar shadows; bit 2: every plant at n_max; bits 8–15: MSAA samples
  float lodDistanceM;    // eq. 4's distance unit: full detail within it
  float tableLogKMin;    // ln of the table's first stiffness
  float tableLogKStep;   // ln step between rows
  uint tableRows;
  float shadowDistanceM; // planar shadows fade out over its last quarter (plant_shape.glsl)
} pc;

const uint kFlagShadows = 1u;
const uint kFlagFlatColour = 2u;  // plant.frag: flat magenta, for coverage measures
const uint kFlagFullDetail = 4u;
const uint kFlagHardFades = 65536u;  // --plant-fades off: segment counts step, no morph

#include "simulation_fields.glsl"
#include "plant_params.glsl"

// The imagery colour (linear) under a point of the triangle at (r′1, r′2).
vec3 groundColour(SeedTriangle t, vec2 r) {
  vec2 uv0 = t.uv01.xy;
  vec2 uv = uv0 + r.x * (t.uv01.zw - uv0) + r.y * (t.uv2 - uv0);
  return texture(imagery, vec3(uv, float(t.layer))).rgb;
}

// The blade's point at fraction x of its length from the root: (lateral, height) for a blade of
// unit length, and the inclination from vertical there — from the solved shapes
// (vegetation/blade_shape.h), rows spaced evenly in ln k′, bilinear between rows and along
// the segment chain (its end points, the root at (0, 0)).
vec3 bladeRow(int row, float x) {
  int n = textureSize(bladeTable, 0).x;
  float s = clamp(x, 0.0, 1.0) * float(n);
  int j = min(int(s), n - 1);
  float f = s - float(j);
  vec4 b = texelFetch(bladeTable, ivec2(j, row), 0);
  vec4 a = j == 0 ? vec4(0.0, 0.0, b.z, 0.0) : texelFetch(bladeTable, ivec2(j - 1, row), 0);
  return vec3(mix(a.xy, b.xy, f) / float(n), b.z);
}

vec3 bladePoint(float stiffness, float x) {
  float rowF = clamp((log(max(stiffness, 1e-6)) - pc.tableLogKMin) / pc.tableLogKStep, 0.0, float(pc.tableRows - 1u));
  int r0 = int(rowF);
  int r1 = min(r0 + 1, int(pc.tableRows) - 1);
  return mix(bladeRow(r0, x), bladeRow(r1, x), rowF - float(r0));
}

// A point of a plant's blade at fraction x of its length (core seed 001 §2.3): on the solved
// shape, rotated about the vertical by the plant's orientation and scaled by its height. The
// tessellation path (plant.tese) and the compute path (blades.comp) both place vertices here.
struct BladeVertexFrame {
  vec3 pos;     // camera-relative
  vec3 side;    // unit, across the blade
  vec3 normal;  // unit, the blade's face
  float along;  // 0 root … 1 tip: where the vertex is along the blade (its width, its texture)
};

BladeVertexFrame bladeVertexFrame(PlantParams p, float x) {
  vec3 shape = bladePoint(p.stiffness, x);
  vec3 dir = vec3(cos(p.orientation), sin(p.orientation), 0.0);
  vec3 up = vec3(0.0, 0.0, 1.0);
  BladeVertexFrame f;
  vec3 along = dir * shape.x + up * shape.y;  // unit length, relative to the root
  f.side = vec3(-dir.y, dir.x, 0.0);
  vec3 tangent = dir * sin(shape.z) + up * cos(shape.z);
  f.normal = normalize(cross(f.side, tangent));
  if (p.bend.moving > 0.5) {  // the shared simulation's wind, trails and colliders
    along = bendPoint(p.bend, p.rest, along, x);
    f.side = bendVector(p.bend, f.side, x);
    f.normal = bendVector(p.bend, f.normal, x);
  }
  f.pos = p.root + along * p.height;
  f.along = x;
  return f;
}

// The blade's rest point at fraction x, relative to the root, unit length, world-oriented.
vec3 restAlong(PlantParams p, float x) {
  vec3 shape = bladePoint(p.stiffness, x);
  return vec3(cos(p.orientation), sin(p.orientation), 0.0) * shape.x + vec3(0.0, 0.0, shape.y);
}

// The shared simulation's bend of a plant of `kind` (issue 19; simulation/shared/blade_response.glsl):
// its equilibrium under the wind grid's moments, the interaction field's flattening and the
// frame's colliders. Gravel (kind 1) does not move; nothing moves while the simulation is off.
void plantMotion(inout PlantParams p, uint kind) {
  int flags = sim.counts.z;
  if (kind == 1u || (flags & (kSimFlagWind | kSimFlagInteraction)) == 0) return;
  for (int i = 0; i < kBladeHinges; ++i) {
    p.rest.hinge[i] = restAlong(p, float(i) / float(kBladeHinges));
    p.rest.centre[i] = restAlong(p, (float(i) + 0.5) / float(kBladeHinges));
  }
  if ((flags & kSimFlagWind) != 0) {
    p.bend = solveBladeBend(p.rest, momentsAt(p.root), p.stiffness);
  } else {
    for (int i = 0; i < kBladeHinges; ++i) p.bend.hinge[i] = vec2(0.0);
    p.bend.root = vec4(0.0, 0.0, 0.0, 1.0);
    p.bend.moving = 1.0;
  }
  if ((flags & kSimFlagInteraction) != 0) {
    vec3 tip = bendPoint(p.bend, p.rest, restAlong(p, 1.0), 1.0) * p.height;
    p.bend.root = colliderTurn(p.root, tip, leanQuat(flattenLean(interactionAt(p.root), p.stiffness)));
  }
  // A blade laid down (by the wind, a rotor's downwash, a trail) is the top of an opened canopy:
  // nothing shades it (plant_lighting.glsl's occlusion takes max(along, pressed)), and it shows
  // its blades' light faces all one way (why a trail or a downwash reads from afar): up to 20 %
  // brighter as its tip comes down to the ground.
  vec3 rest = restAlong(p, 1.0);
  vec3 bent = bendPoint(p.bend, p.rest, rest, 1.0);
  p.pressed = clamp(1.0 - bent.z / max(rest.z, 0.05), 0.0, 1.0);
  p.colourModulation *= 1.0 + 0.2 * p.pressed;
}

// Vertex j of a blade of n segments whose last segment has grown in by `grown` (groupLod's z),
// on both blade paths. At grown = 0 the blade is the (n − 1)-segment blade exactly — vertex j sits
// on that blade's vertex min(j, n − 1), so its last segment has no length — and as it grows each
// vertex slides (position, frame, and where it is along the blade: width and texture) to its own
// place at x = j / n. A blade gaining or losing a segment thus changes shape continuously: no
// corner of the coarser blade is cut at the switch (tests/render/blade_path_test.cpp
// SegmentCountsMorphInsteadOfStepping).
BladeVertexFrame morphedBladeFrame(PlantParams p, uint j, uint n, float grown) {
  BladeVertexFrame f = bladeVertexFrame(p, float(j) / float(n));
  if (grown >= 1.0 || n <= 1u) return f;
  BladeVertexFrame c = bladeVertexFrame(p, float(min(j, n - 1u)) / float(n - 1u));
  f.pos = mix(c.pos, f.pos, grown);
  f.side = normalize(mix(c.side, f.side, grown));
  f.normal = normalize(mix(c.normal, f.normal, grown));
  f.along = mix(c.along, f.along, grown);
  return f;
}

// The distance from the camera to the nearest point of the seed triangle's bounding sphere
// (centroid, farthest vertex), 0 inside it.
// seedTriangleNearestM for the shadow test (plant_shape.glsl shadowsReach): infinitely far for a
// species that casts no planar shadows (flags.z 0: its blades cover the ground they would fall on).
float seedTriangleNearestM(SeedTriangle t);
float shadowNearestM(PlantCluster g, SeedTriangle t) {
  return catalog.species[g.species].flags.z != 0u ? seedTriangleNearestM(t) : 3.0e38;
}

float seedTriangleNearestM(SeedTriangle t) {
  vec3 c = (t.v0.xyz + t.v1.xyz + t.v2.xyz) / 3.0;
  float r = sqrt(max(max(dot(t.v0.xyz - c, t.v0.xyz - c), dot(t.v1.xyz - c, t.v1.xyz - c)), dot(t.v2.xyz - c, t.v2.xyz - c)));
  return max(length(c) - r, 0.0);
}
