// One drawn terrain piece, in draw order (mirrors TerrainPiece in render/terrain_pass.h): what
// the terrain's draws (terrain_draw.glsl) and the compute passes (terrain_geometry.glsl) read.
#ifndef TERRAIN_PIECE_GLSL
#define TERRAIN_PIECE_GLSL
struct Piece {
  vec4 originFromCamera;  // xyz: mesh origin − camera position (m, local ENU); w: unused
  vec4 imageryUv;         // layer uv = vertex uv · xy + zw
  vec4 previousUv;        // the same for the layer it fades from
  vec4 layers;            // x: imagery layer (−1 none), y: previous layer (−1 none), z: blend 0 previous … 1 current
  uvec4 range;            // x: first triangle, y: first vertex (the draw's vertex offset), z: triangles
};
#endif
