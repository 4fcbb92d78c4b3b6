#version 450
#extension GL_GOOGLE_include_directive : require
// Classification markers: flat species colour.
#include "frame_uniforms.glsl"
layout(location = 0) in vec3 inColour;
layout(location = 0) out vec4 outColor;
void main() {
  outColor = vec4(inColour, 1.0);
}
