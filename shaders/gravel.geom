#version 450
#extension GL_GOOGLE_include_directive : require
// Gravel (core seed 001 fig. 1): one small diamond per plant standing on its root and facing
// the camera, as large as the plant's larger dimension (never under 1.5 pixels); invocation 1
// is its planar shadow.
layout(lines, invocations = 2) in;
layout(triangle_strip, max_vertices = 4) out;
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
  vec3 root = inPos[0];
  float px = 1.5 * metresPerPixel(length(root));  // at least 1.5 pixels across
  float size = max(max(inPlant[0].x, inPlant[0].z), px);
  // Facing the camera, so a stone reads as a stone from any height; its foot on the ground.
  vec3 view = normalize(root);
  vec3 groundN = inPlane[0].xyz;
  vec3 right = cross(view, groundN);
  right = length(right) > 1e-3 ? normalize(right) : inSide[0];
  vec3 up = normalize(cross(right, view));
  if (dot(up, groundN) < 0.0) up = -up;
  vec3 side = right * (0.5 * size), rise = up * (0.4 * size);
  vec3 n = normalize(-view + groundN);
  vec4 plant = vec4(inPlant[0].y, inPlant[0].w, 1.0, 0.0);
  vec3 c = root + rise;
  emitPlantVertex(c - side, n, vec2(-1.0, 0.5), inGround[0], plant, shadow, inPlane[0]);
  emitPlantVertex(c - rise, n, vec2(0.0, 0.0), inGround[0], plant, shadow, inPlane[0]);
  emitPlantVertex(c + rise, n, vec2(0.0, 1.0), inGround[0], plant, shadow, inPlane[0]);
  emitPlantVertex(c + side, n, vec2(1.0, 0.5), inGround[0], plant, shadow, inPlane[0]);
  EndPrimitive();
}
