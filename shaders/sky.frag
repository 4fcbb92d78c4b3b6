#version 450
#extension GL_GOOGLE_include_directive : require
#include "frame_uniforms.glsl"
#include "atmosphere.glsl"
#include "aov.glsl"
layout(location = 0) in vec2 inNdc;
layout(location = 0) out vec4 outColor;
void main() {
  vec4 p = frame.invViewProj * vec4(inNdc, 0.5, 1.0);
  vec3 dir = normalize(p.xyz / p.w);
  outColor = aovGround(vec4(ditheredSky(skyColor(dir), uvec2(gl_FragCoord.xy)), 1.0));
}
