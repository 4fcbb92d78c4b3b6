// Per group, what the tessellation control stage (plant.tesc) and the compute blade expansion
// (blades.comp) both decide, with the same arithmetic so both paths draw the same blades: whether
// the group's bounding sphere is in the view frustum, and each blade's segment count
// n = n_max / max(‖v‖, 1)² (core seed 001_3eca9f2c7752e4fb.txt §2.3 eq. 4, ‖v‖ in units of
// lodDistanceM, rounded up; gravel: 1). Needs frame_uniforms.glsl, classify_layout.glsl and
// plant_common.glsl.

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

// x: 1 when the group is in view, else 0; y: segments per blade (1 … n_max, a whole number);
// z: how far the last segment has grown in, 0 … 1 (issue 18: segment counts morph instead of
// stepping). The blade has y segments; at z = 0 it is the (y − 1)-segment blade exactly (its last
// segment has no length: morphedBladeFrame, plant_common.glsl), at 1 on the solved shape.
vec3 groupLod(PlantCluster g, SeedTriangle t) {
  Species sp = catalog.species[g.species];
  vec3 centre = (t.v0.xyz + t.v1.xyz + t.v2.xyz) / 3.0;
  float radius = max(max(length(t.v0.xyz - centre), length(t.v1.xyz - centre)), length(t.v2.xyz - centre)) +
                 sp.heightStiffness.y;
  bool visible = sphereVisible(centre, radius);
  float d = max(length(centre) - radius, 0.0) / pc.lodDistanceM;
  float nf = (pc.flags & kFlagFullDetail) != 0u ? float(pc.maxSegments) : float(pc.maxSegments) / pow(max(d, 1.0), 2.0);
  float n = clamp(ceil(nf), 1.0, float(pc.maxSegments));
  float grown = n <= 1.0 ? 1.0 : clamp(nf - (n - 1.0), 0.0, 1.0);
  if ((pc.flags & kFlagHardFades) != 0u) grown = 1.0;
  if (sp.flags.y == 1u) {  // gravel: one particle per plant, no segments to bend
    n = 1.0;
    grown = 1.0;
  }
  return vec3(visible ? 1.0 : 0.0, n, grown);
}
