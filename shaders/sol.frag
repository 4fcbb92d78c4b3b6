#version 450
// Speed of light: one constant colour.
layout(location = 0) out vec4 outColor;
void main() { outColor = vec4(0.1, 0.3, 0.05, 1.0); }
