#version 450
// Tone mapping (common/exposure.glsl): the resolved linear HDR frame × the frame's exposure →
// AgX → sRGB-encoded bytes in the display target, which the HUD, the read-back and the window
// take. Identity mode (the flat-colour coverage style) only clamps and encodes, so #ff00ff stays
// #ff00ff.
#extension GL_GOOGLE_include_directive : require
#include "common/exposure.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0, r11f_g11f_b10f) uniform readonly image2D hdr;
layout(set = 0, binding = 1, std430) readonly buffer State { ExposureState state; };
layout(set = 0, binding = 2, rgba8) uniform writeonly image2D displayImage;
layout(push_constant) uniform Push {
  vec4 params;
  uvec4 target;
} pc;

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (px.x >= int(pc.target.y) || px.y >= int(pc.target.z)) return;
  vec3 c = imageLoad(hdr, px).rgb;
  vec3 shown = uint(pc.params.x) == kToneIdentity ? c : agxToneMap(c * exposureScale(state.ev));
  imageStore(displayImage, px, vec4(srgbEncoded(shown), 1.0));
}
