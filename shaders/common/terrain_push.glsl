// Push constants of the terrain pass, one set per draw (mirrors TerrainPush in
// render/terrain_pass.cpp).
layout(push_constant) uniform TerrainPush {
  vec4 originFromCamera;  // xyz: mesh origin − camera position (m, local ENU); w: unused
  vec4 imageryUv;         // layer uv = vertex uv · xy + zw
  vec4 previousUv;        // the same for the layer it fades from
  vec4 layers;            // x: imagery layer (−1 none), y: previous layer (−1 none), z: blend 0 previous … 1 current
  uvec4 ids;              // x: the piece's first triangle in the frame's index buffer (visibility ids)
} push;
