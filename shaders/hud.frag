#version 450
// The HUD overlay: vertex colour times the font atlas (straight alpha, blended by the pipeline).
layout(set = 0, binding = 0) uniform sampler2D atlas;  // UNORM view: alpha is coverage
layout(location = 0) in vec2 inUv;
layout(location = 1) in vec4 inColor;
layout(location = 0) out vec4 outColor;

void main() {
  outColor = inColor * texture(atlas, inUv);
}
