#version 450
#extension GL_GOOGLE_include_directive : require
// Flowers and dry tufts: a thin stem like a grass blade and, on the stem's last segment, a small
// flower head facing up (the third renderer kind: one shader plus catalog data); invocation 1
// is the planar shadow of both.
layout(lines, invocations = 2) in;
layout(triangle_strip, max_vertices = 8) out;
#include "frame_uniforms.glsl"
#include "philox.glsl"
#include "seeding.glsl"
#include "classify_layout.glsl"
#include "plant_common.glsl"
#include "plant_geometry.glsl"

layout(location = 0) in vec3 inPos[];
layout(location = 1) in vec3 inSide[];
layout(location = 2) in vec3 inNormal[];
layout(location = 3) in float inAlong[];
layout(location = 4) in vec3 inGround[];
layout(location = 5) in vec4 inPlant[];
layout(location = 6) in vec4 inPlane[];
layout(location = 7) in float inNearest[];

void main() {
  bool shadow = gl_InvocationID == 1;
  if (shadow && ((pc.flags & kFlagShadows) == 0u || !castsShadow(inPlane[0]) || !shadowsReach(inNearest[0]))) return;
  vec4 stem = vec4(inPlant[0].y, inPlant[0].w, 0.0, 0.0);
  for (int i = 0; i < 2; ++i) {
    float halfWidth = 0.5 * max(0.5 * inPlant[i].x, metresPerPixel(length(inPos[i])));
    for (int s = -1; s <= 1; s += 2)
      emitPlantVertex(inPos[i] + inSide[i] * (float(s) * halfWidth), inNormal[i], vec2(float(s), inAlong[i]),
                      inGround[0], stem, shadow, inPlane[0]);
  }
  EndPrimitive();
  if (inAlong[1] < 0.999) return;
  // The head: a square lying across the stem's tip, a few widths across.
  float r = max(2.5 * inPlant[0].x, 1.5 * metresPerPixel(length(inPos[1])));
  vec3 tip = inPos[1];
  vec3 a = inSide[1] * r, b = cross(vec3(0.0, 0.0, 1.0), inSide[1]) * r;
  vec4 head = vec4(inPlant[0].y, inPlant[0].w, 2.0, 0.0);
  vec3 n = vec3(0.0, 0.0, 1.0);
  emitPlantVertex(tip - a - b, n, vec2(-1.0, 0.0), inGround[0], head, shadow, inPlane[0]);
  emitPlantVertex(tip + a - b, n, vec2(1.0, 0.0), inGround[0], head, shadow, inPlane[0]);
  emitPlantVertex(tip - a + b, n, vec2(-1.0, 1.0), inGround[0], head, shadow, inPlane[0]);
  emitPlantVertex(tip + a + b, n, vec2(1.0, 1.0), inGround[0], head, shadow, inPlane[0]);
  EndPrimitive();
}
