// Geometry-stage helpers shared by the plant kinds: the outputs every plant fragment gets and
// emitPlantVertex, which places and lights a vertex (plant_lighting.glsl) or, in a second
// geometry invocation, places its planar shadow of core seed 001_3eca9f2c7752e4fb.txt §3.6
// (plant_shape.glsl). blade.vert writes the same outputs. Needs frame_uniforms.glsl.

layout(location = 0) out vec3 gColour;      // lit, after aerial perspective (linear); shadows: r = coverage
layout(location = 1) out vec2 gBlade;       // x: −1 … 1 across, y: 0 root … 1 tip
layout(location = 2) flat out uint gFlags;  // bits 0–1: kind (0 blade, 1 stone, 2 flower head); bit 2: shadow; bits 3–7: species

#include "atmosphere.glsl"
#include "plant_lighting.glsl"
#include "plant_shape.glsl"

// plant: x colour modulation, y pressed 0 … 1 (lit as the canopy's top: plantMotion), z kind.
void emitPlantVertex(vec3 p, vec3 n, vec2 blade, vec3 ground, vec4 plant, bool shadow, vec4 plane) {
  uint kind = uint(plant.z + 0.5);
  vec3 q = shadow ? shadowPoint(p, plane) : p;
  gColour = shadow ? vec3(shadowStrength(p), 0.0, 0.0) : plantColour(q, n, vec2(blade.x, max(blade.y, plant.y)), ground, plant.x, kind, plane.xyz);
  gBlade = blade;
  gFlags = kind | (shadow ? 4u : 0u) | (pc.species << 3u);
  gl_Position = frame.viewProj * vec4(q, 1.0);
  EmitVertex();
}
