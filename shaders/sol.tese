#version 450
#extension GL_GOOGLE_include_directive : require
// Speed of light (bench/bench_plants.cpp): the same isolines as plant.tese — same patches,
// plants and segments — with the least work: a straight vertical line at a cheap spot of the
// seed triangle, no hashing, no shape table, no imagery.
layout(isolines, equal_spacing) in;
#include "frame_uniforms.glsl"
#include "philox.glsl"
#include "seeding.glsl"
#include "classify_layout.glsl"
#include "plant_common.glsl"

layout(location = 0) patch in uint group;
layout(location = 0) out vec3 outPos;

void main() {
  PlantCluster g = records[pc.species * pc.speciesCapacity + group];
  SeedTriangle t = triangles[g.triangle];
  float l = gl_TessCoord.y * gl_TessLevelOuter[0];
  vec2 r = fract(vec2(0.618034, 0.381966) * (l + 1.0)) * 0.5;
  vec3 root = t.v0.xyz + r.x * (t.v1.xyz - t.v0.xyz) + r.y * (t.v2.xyz - t.v0.xyz);
  outPos = root + vec3(0.0, 0.0, 0.4 * gl_TessCoord.x);
}
