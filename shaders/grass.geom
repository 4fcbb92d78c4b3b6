#version 450
#extension GL_GOOGLE_include_directive : require
// Grass (core seed 001 §2.3): each line segment of the blade extruded along its side vector into
// a quad, tapering to the tip; invocation 1 is its planar shadow (§3.6) when shadows are on.
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
  vec4 plant = vec4(inPlant[0].y, inPlant[0].w, 0.0, 0.0);
  for (int i = 0; i < 2; ++i) {
    // Never thinner than 1.5 pixels: plant density falls with the projected area (eq. 1), so a
    // far blade must cover more of its share of the screen for the canopy to stay closed.
    float width = max(inPlant[i].x, 1.5 * metresPerPixel(length(inPos[i])));
    float halfWidth = 0.5 * width * pow(1.0 - inAlong[i], 0.7);
    for (int s = -1; s <= 1; s += 2)
      emitPlantVertex(inPos[i] + inSide[i] * (float(s) * halfWidth), inNormal[i], vec2(float(s), inAlong[i]),
                      inGround[0], plant, shadow, inPlane[0]);
  }
  EndPrimitive();
}
