// The plant kinds' geometry helpers, shared by the geometry shaders (plant_geometry.glsl) and
// the compute blade expansion (blades.comp), so both paths place every vertex with the same
// arithmetic: the planar shadow of core seed 001_3eca9f2c7752e4fb.txt §3.6 (the plant's geometry
// projected along the sunlight onto its seed triangle's plane) and the pixel footprint that keeps
// far blades 1.5 pixels wide. Needs frame_uniforms.glsl and plant_common.glsl (pc).

// Where `p` falls on the plane (unit normal n, offset d) along the sun's rays, lifted 1.5 cm so
// it does not fight the terrain for depth.
vec3 shadowPoint(vec3 p, vec4 plane) {
  vec3 l = frame.sunDirection.xyz;
  float t = (dot(plane.xyz, p) + plane.w) / max(dot(plane.xyz, l), 1e-3);
  return p - l * t + plane.xyz * 0.015;
}

// Metres one pixel spans at distance `d` (the rotation-only view keeps the projection's y scale
// as the length of viewProj's second row).
float metresPerPixel(float d) {
  mat4 m = frame.viewProj;
  float focal = 0.5 * frame.viewport.y * length(vec3(m[0][1], m[1][1], m[2][1]));
  return d / focal;
}

// The sun is high enough over the plane for a planar shadow.
bool castsShadow(vec4 plane) { return dot(plane.xyz, frame.sunDirection.xyz) > 0.05; }

// Planar shadows end at pc.shadowDistanceM, fading out over its last quarter (the coverage of a
// shadow point at `p`, 1 … 0). Beyond a few tens of metres a blade's shadow is a streak 1.5 pixels
// wide that only darkens the ground, yet with a low sun it is many times the blade's area: on the
// H200 the shadows were three quarters of a dense field's plants pass (render/README.md).
float shadowStrength(vec3 p) {
  return 1.0 - smoothstep(0.75 * pc.shadowDistanceM, pc.shadowDistanceM, length(p));
}

// A seed triangle's plants may cast a visible shadow: the nearest point of its bounding sphere
// is inside the shadow distance. `nearestM`: seedTriangleNearestM (plant_common.glsl). The same
// test per group on both blade paths, so they draw the same shadow triangles.
bool shadowsReach(float nearestM) { return nearestM < pc.shadowDistanceM; }
