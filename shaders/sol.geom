#version 450
// Speed of light: each segment a fixed-width quad, one invocation, nothing else.
layout(lines) in;
layout(triangle_strip, max_vertices = 4) out;
layout(set = 0, binding = 0, std140) uniform FrameUniforms {
  mat4 viewProj;
} frame;
layout(location = 0) in vec3 inPos[];
void main() {
  const vec3 side = vec3(0.01, 0.0, 0.0);
  for (int i = 0; i < 2; ++i) {
    gl_Position = frame.viewProj * vec4(inPos[i] - side, 1.0);
    EmitVertex();
    gl_Position = frame.viewProj * vec4(inPos[i] + side, 1.0);
    EmitVertex();
  }
  EndPrimitive();
}
