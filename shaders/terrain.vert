#version 450
#extension GL_GOOGLE_include_directive : require
#include "frame_uniforms.glsl"
// Terrain vertices are float offsets from their mesh's origin; the push constant carries
// origin − camera, computed in double on the CPU. Adding the two here keeps centimetre
// precision kilometres from the origin (positions relative to the camera).
layout(push_constant) uniform TerrainPush {
  vec4 originFromCamera;  // xyz: mesh origin − camera position (m, local ENU)
} push;
layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in float inHeightMsl;
layout(location = 0) out vec3 outOffset;   // camera-relative position
layout(location = 1) out vec3 outNormal;
layout(location = 2) out float outHeightMsl;
void main() {
  vec3 offset = inPosition + push.originFromCamera.xyz;
  outOffset = offset;
  outNormal = inNormal;
  outHeightMsl = inHeightMsl;
  gl_Position = frame.viewProj * vec4(offset, 1.0);
}
