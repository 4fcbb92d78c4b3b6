// Push constants of the terrain pass (mirrors TerrainPush in render/terrain_pass.cpp).
layout(push_constant) uniform TerrainPush {
  vec4 originFromCamera;  // xyz: mesh origin − camera position (m, local ENU)
  vec4 flags;             // x: 1 when the imagery texture colours the terrain
} push;
