#version 450
#extension GL_GOOGLE_include_directive : require
// Speed of light: one constant colour.
#include "frame_uniforms.glsl"
layout(location = 0) out vec4 outColor;
void main() {
  outColor = vec4(0.1, 0.3, 0.05, 1.0);
}
