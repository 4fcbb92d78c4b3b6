#version 450
#extension GL_GOOGLE_include_directive : require
#include "frame_uniforms.glsl"
#include "terrain_draw.glsl"
// The visibility pass's vertex stage: terrain.vert's position and nothing else (the shade pass
// interpolates the attributes itself from the triangle it finds).
layout(location = 0) in vec3 inPosition;
layout(location = 0) flat out uint outPiece;
void main() {
  outPiece = uint(gl_InstanceIndex);
  gl_Position = frame.viewProj * vec4(inPosition + drawPieces[gl_InstanceIndex].originFromCamera.xyz, 1.0);
}
