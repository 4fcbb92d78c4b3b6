// Geometry-stage helpers shared by the plant kinds: the outputs every plant fragment gets and
// the planar shadow of core seed 001_3eca9f2c7752e4fb.txt §3.6 (the plant's geometry projected
// along the sunlight onto its seed triangle's plane, drawn by a second geometry invocation).
// Needs frame_uniforms.glsl.

layout(location = 0) out vec3 gPos;       // camera-relative
layout(location = 1) out vec3 gNormal;
layout(location = 2) out vec2 gBlade;     // x: −1 … 1 across, y: 0 root … 1 tip
layout(location = 3) flat out vec3 gGround;
layout(location = 4) flat out vec4 gPlant;  // colour modulation, s′, kind-specific, shadow (1)
layout(location = 5) flat out vec3 gUp;     // the ground's normal under the plant

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

void emitPlantVertex(vec3 p, vec3 n, vec2 blade, vec3 ground, vec4 plant, bool shadow, vec4 plane) {
  vec3 q = shadow ? shadowPoint(p, plane) : p;
  gPos = q;
  gNormal = shadow ? plane.xyz : n;
  gBlade = blade;
  gGround = ground;
  gPlant = vec4(plant.xyz, shadow ? 1.0 : 0.0);
  gUp = plane.xyz;
  gl_Position = frame.viewProj * vec4(q, 1.0);
  EmitVertex();
}
