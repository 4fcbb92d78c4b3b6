#version 450
// The HUD overlay (render/hud_pass.cpp): pixel positions → clip space, colour sRGB → linear
// (the target is sRGB, so the hardware encodes it back on write).
layout(location = 0) in vec2 inPos;
layout(location = 1) in vec2 inUv;
layout(location = 2) in vec4 inColor;  // RGBA8 unorm, sRGB-encoded
layout(push_constant) uniform Push {
  vec2 scale;      // 2 / layout size
  vec2 translate;  // −1
} push;
layout(location = 0) out vec2 outUv;
layout(location = 1) out vec4 outColor;

vec3 srgbToLinear(vec3 c) {
  return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), step(0.04045, c));
}

void main() {
  outUv = inUv;
  outColor = vec4(srgbToLinear(inColor.rgb), inColor.a);
  gl_Position = vec4(inPos * push.scale + push.translate, 0.0, 1.0);
}
