#version 450
#extension GL_GOOGLE_include_directive : require
// Each isoline is one plant of the group (core seed 001 §2.3): its root in the cluster's stratum
// (shaders/common/seeding.glsl), its parameters from the species ranges, and each vertex on the
// solved blade shape (sampled by stiffness and position along the blade), rotated about the
// vertical by the plant's orientation and scaled by its height.
layout(isolines, equal_spacing) in;
#include "frame_uniforms.glsl"
#include "philox.glsl"
#include "seeding.glsl"
#include "classify_layout.glsl"
#include "plant_common.glsl"
#include "plant_lod.glsl"

layout(location = 0) patch in uint group;
layout(location = 0) out vec3 outPos;      // camera-relative
layout(location = 1) out vec3 outSide;     // unit, across the blade
layout(location = 2) out vec3 outNormal;   // unit, the blade's face
layout(location = 3) out float outAlong;   // 0 at the root … 1 at the tip
layout(location = 4) out vec3 outGround;   // the imagery colour under the root (linear)
layout(location = 5) out vec4 outPlant;    // width (m), colour modulation, height (m), pressed 0 … 1
layout(location = 6) out vec4 outPlane;    // the seed triangle's plane: unit normal, offset (camera-relative)
layout(location = 7) out float outNearest; // seedTriangleNearestM: whether its shadows are drawn

void main() {
  PlantCluster g = records[pc.species * pc.speciesCapacity + group];
  SeedTriangle t = triangles[g.triangle];
  uint lines = max(uint(gl_TessLevelOuter[0] + 0.5), 1u);
  uint l = min(uint(gl_TessCoord.y * float(lines) + 0.5), lines - 1u);
  uint seed = g.firstSeed + l;
  PlantParams p = plantParams(g, t, seed);
  plantMotion(p, catalog.species[g.species].flags.y);
  // Vertex j of n (equal spacing: x = j / n, taken exactly as the compute path does).
  uint n = max(uint(gl_TessLevelOuter[1] + 0.5), 1u);
  uint j = min(uint(gl_TessCoord.x * float(n) + 0.5), n);
  BladeVertexFrame f = morphedBladeFrame(p, j, n, groupLod(g, t).z);
  outPos = f.pos;
  outSide = f.side;
  outNormal = f.normal;
  outAlong = f.along;
  vec2 r = seedPoint(uvec2(t.keyLo, t.keyHi), g.cluster, seed);
  outGround = groundColour(t, r);
  outPlant = vec4(p.width, p.colourModulation, p.height, p.pressed);
  vec3 nrm = normalize(cross(t.v1.xyz - t.v0.xyz, t.v2.xyz - t.v0.xyz));
  outPlane = vec4(nrm, -dot(nrm, t.v0.xyz));
  outNearest = shadowNearestM(g, t);
}
