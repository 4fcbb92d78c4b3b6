// Geometry-stage helpers shared by the plant kinds: the outputs every plant fragment gets and
// emitPlantVertex, which places a vertex or (a second geometry invocation) its planar shadow of
// core seed 001_3eca9f2c7752e4fb.txt §3.6 (plant_shape.glsl). Needs frame_uniforms.glsl.

layout(location = 0) out vec3 gPos;       // camera-relative
layout(location = 1) out vec3 gNormal;
layout(location = 2) out vec2 gBlade;     // x: −1 … 1 across, y: 0 root … 1 tip
layout(location = 3) flat out vec3 gGround;
layout(location = 4) flat out vec4 gPlant;  // colour modulation, s′, kind-specific, shadow (1)
layout(location = 5) flat out vec3 gUp;     // the ground's normal under the plant

#include "plant_shape.glsl"

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
