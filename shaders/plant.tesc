#version 450
#extension GL_GOOGLE_include_directive : require
// Per group: as many isolines as it has plants, each of n segments, n = n_max / max(‖v‖, 1)²
// (core seed 001_3eca9f2c7752e4fb.txt §2.3 eq. 4, ‖v‖ in units of lodDistanceM, rounded up);
// a group whose bounding sphere is outside the view frustum gets no lines at all.
layout(vertices = 1) out;
#include "frame_uniforms.glsl"
#include "philox.glsl"
#include "seeding.glsl"
#include "classify_layout.glsl"
#include "plant_common.glsl"

layout(location = 0) in uint inGroup[];
layout(location = 0) patch out uint group;

bool sphereVisible(vec3 c, float r) {
  mat4 m = frame.viewProj;
  vec4 row0 = vec4(m[0][0], m[1][0], m[2][0], m[3][0]);
  vec4 row1 = vec4(m[0][1], m[1][1], m[2][1], m[3][1]);
  vec4 row3 = vec4(m[0][3], m[1][3], m[2][3], m[3][3]);
  vec4 planes[5] = vec4[5](row3 + row0, row3 - row0, row3 + row1, row3 - row1, row3);
  for (int i = 0; i < 5; ++i)
    if (dot(planes[i].xyz, c) + planes[i].w < -r * length(planes[i].xyz)) return false;
  return true;
}

void main() {
  uint gi = inGroup[0];
  group = gi;
  PlantCluster g = records[pc.species * pc.speciesCapacity + gi];
  SeedTriangle t = triangles[g.triangle];
  Species sp = catalog.species[g.species];
  vec3 centre = (t.v0.xyz + t.v1.xyz + t.v2.xyz) / 3.0;
  float radius = max(max(length(t.v0.xyz - centre), length(t.v1.xyz - centre)), length(t.v2.xyz - centre)) +
                 sp.heightStiffness.y;
  bool visible = sphereVisible(centre, radius);
  float d = max(length(centre) - radius, 0.0) / pc.lodDistanceM;
  float n = (pc.flags & kFlagFullDetail) != 0u ? float(pc.maxSegments) : ceil(float(pc.maxSegments) / pow(max(d, 1.0), 2.0));
  if (sp.flags.y == 1u) n = 1.0;  // gravel: one particle per plant, no segments to bend
  gl_TessLevelOuter[0] = visible ? float(g.seedCount) : 0.0;
  gl_TessLevelOuter[1] = clamp(n, 1.0, float(pc.maxSegments));
}
