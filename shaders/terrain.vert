#version 450
#extension GL_GOOGLE_include_directive : require
#include "frame_uniforms.glsl"
#include "terrain_draw.glsl"
// Terrain vertices are float offsets from their mesh's origin; the piece carries
// origin − camera, computed in double on the CPU. Adding the two here keeps centimetre
// precision kilometres from the origin (positions relative to the camera).
// Geomorphing happens on the CPU (terrain/roam_mesh.h): the vertices arrive at their drawn heights.
layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in float inHeightMsl;
layout(location = 3) in vec2 inUv;
layout(location = 0) out vec3 outOffset;   // camera-relative position
layout(location = 1) out vec3 outNormal;
layout(location = 2) out float outHeightMsl;
layout(location = 3) out vec2 outUv;
layout(location = 4) flat out uint outPiece;
void main() {
  outPiece = uint(gl_InstanceIndex);
  vec3 offset = inPosition + drawPieces[gl_InstanceIndex].originFromCamera.xyz;
  outOffset = offset;
  outNormal = inNormal;
  outHeightMsl = inHeightMsl;
  outUv = inUv;
  gl_Position = frame.viewProj * vec4(offset, 1.0);
}
