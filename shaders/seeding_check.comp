#version 450
#extension GL_GOOGLE_include_directive : require
// Test kernel (tests/render/classify_gpu_test.cpp): the root of every plant of the classify
// pass's records, from shaders/common/seeding.glsl — what the species pipelines compute — to be
// compared with vegetation/plant_seeding.cpp.
layout(local_size_x = 64) in;
#include "philox.glsl"
#include "seeding.glsl"
#include "classify_layout.glsl"

layout(set = 0, binding = 0, std430) readonly buffer Triangles { SeedTriangle triangles[]; };
layout(set = 0, binding = 1, std430) readonly buffer Records { PlantCluster records[]; };
layout(set = 0, binding = 2, std430) writeonly buffer Roots { vec4 roots[]; };
layout(push_constant) uniform Push { uint records; uint clusterSize; uint first; } pc;

void main() {
  uint id = gl_GlobalInvocationID.x;
  if (id >= pc.records * pc.clusterSize) return;
  PlantCluster g = records[pc.first + id / pc.clusterSize];
  uint seed = id % pc.clusterSize;
  if (seed >= g.seedCount) {
    roots[id] = vec4(0.0, 0.0, 0.0, -1.0);
    return;
  }
  SeedTriangle t = triangles[g.triangle];
  vec2 r = seedPoint(uvec2(t.keyLo, t.keyHi), g.cluster, g.firstSeed + seed);
  roots[id] = vec4(t.v0.xyz + r.x * (t.v1.xyz - t.v0.xyz) + r.y * (t.v2.xyz - t.v0.xyz), 1.0);
}
