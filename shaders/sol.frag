#version 450
#extension GL_GOOGLE_include_directive : require
// Speed of light: one constant colour (and, as every plant fragment, the test against a terrain
// rasterised in compute, common/terrain_occlusion.glsl, so the comparison stays fair).
#include "frame_uniforms.glsl"
#include "terrain_occlusion.glsl"
layout(location = 0) out vec4 outColor;
void main() {
  uint visible = terrainCoverage(terrainDepthSlope());
  if (visible == 0u) discard;
  gl_SampleMask[0] = int(visible);
  outColor = vec4(0.1, 0.3, 0.05, 1.0);
}
