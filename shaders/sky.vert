#version 450
#extension GL_GOOGLE_include_directive : require
// A full-screen triangle at the far plane (depth 0 with reverse-Z).
layout(location = 0) out vec2 outNdc;
void main() {
  vec2 uv = vec2((gl_VertexIndex << 1) & 2, gl_VertexIndex & 2);
  outNdc = uv * 2.0 - 1.0;
  gl_Position = vec4(outNdc, 0.0, 1.0);
}
