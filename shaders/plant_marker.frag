#version 450
#extension GL_GOOGLE_include_directive : require
// Classification markers: flat species colour (behind a terrain rasterised in compute: dropped,
// common/terrain_occlusion.glsl).
#include "frame_uniforms.glsl"
#include "terrain_occlusion.glsl"
layout(location = 0) in vec3 inColour;
layout(location = 0) out vec4 outColor;
void main() {
  uint visible = terrainCoverage(terrainDepthSlope());
  if (visible == 0u) discard;
  gl_SampleMask[0] = int(visible);
  outColor = vec4(inColour, 1.0);
}
