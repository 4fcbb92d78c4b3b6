// The terrain geometry of a frame slot as the compute passes read it (render/terrain_pass.h:
// TerrainGeometry): the deferred shade (terrain_shade.glsl) and the compute rasteriser's binning
// (terrain_bin.comp). Set 3, bindings 1–3, and the push constants of those passes.
#ifndef TERRAIN_GEOMETRY_GLSL
#define TERRAIN_GEOMETRY_GLSL

// terrain::TerrainVertex (36 bytes: position, normal, heightMsl, uv), read as floats.
layout(std430, set = 3, binding = 1) readonly buffer Vertices { float vertexData[]; };
layout(std430, set = 3, binding = 2) readonly buffer Indices { uint indexData[]; };
// One per drawn piece, in draw order.
#include "terrain_piece.glsl"
layout(std430, set = 3, binding = 3) readonly buffer Pieces { Piece pieces[]; };
// Mirrors TerrainComputePush (render/terrain_shade_pass.h).
layout(push_constant) uniform ShadePush {
  uvec4 counts;  // x: pieces, y: triangles, z: binning phase (terrain_bin.comp), w: tile list capacity
  uvec4 tiles;   // x, y: tiles across and down (terrain_raster.glsl), z: samples per pixel
} shade;

const int kVertexFloats = 9;

// A point on the ray from the camera (the origin) through `ndc`.
vec3 rayThrough(vec2 ndc) {
  vec4 p = frame.invViewProj * vec4(ndc, 0.5, 1.0);
  return p.xyz / p.w;
}

// The piece that holds triangle `tri`: pieces are in draw order with increasing first triangles.
uint pieceOf(uint tri) {
  uint lo = 0u, hi = shade.counts.x - 1u;
  while (lo < hi) {
    uint mid = (lo + hi + 1u) / 2u;
    if (pieces[mid].range.x <= tri) lo = mid; else hi = mid - 1u;
  }
  return lo;
}

vec3 vertexPosition(uint v) { return vec3(vertexData[v * kVertexFloats], vertexData[v * kVertexFloats + 1], vertexData[v * kVertexFloats + 2]); }
vec3 vertexNormal(uint v) { return vec3(vertexData[v * kVertexFloats + 3], vertexData[v * kVertexFloats + 4], vertexData[v * kVertexFloats + 5]); }
float vertexHeight(uint v) { return vertexData[v * kVertexFloats + 6]; }
vec2 vertexUv(uint v) { return vec2(vertexData[v * kVertexFloats + 7], vertexData[v * kVertexFloats + 8]); }

// Triangle `tri`'s vertex indices (into vertexData) and its piece.
uvec3 triangleVertices(uint tri, Piece pc) {
  return uvec3(indexData[3u * tri], indexData[3u * tri + 1u], indexData[3u * tri + 2u]) + pc.range.y;
}

#endif
