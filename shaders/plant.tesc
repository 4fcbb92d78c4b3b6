#version 450
#extension GL_GOOGLE_include_directive : require
// Per group: as many isolines as it has plants, each of n segments, n = n_max / max(‖v‖, 1)²
// (core seed 001_3eca9f2c7752e4fb.txt §2.3 eq. 4, ‖v‖ in units of lodDistanceM, rounded up);
// a group whose bounding sphere is outside the view frustum gets no lines at all
// (common/plant_lod.glsl, shared with the compute blade path).
layout(vertices = 1) out;
#include "frame_uniforms.glsl"
#include "philox.glsl"
#include "seeding.glsl"
#include "classify_layout.glsl"
#include "plant_common.glsl"
#include "plant_lod.glsl"

layout(location = 0) in uint inGroup[];
layout(location = 0) patch out uint group;

void main() {
  uint gi = inGroup[0];
  group = gi;
  PlantCluster g = records[pc.species * pc.speciesCapacity + gi];
  SeedTriangle t = triangles[g.triangle];
  vec3 lod = groupLod(g, t);
  gl_TessLevelOuter[0] = lod.x > 0.5 ? float(g.seedCount) : 0.0;
  gl_TessLevelOuter[1] = lod.y;
}
