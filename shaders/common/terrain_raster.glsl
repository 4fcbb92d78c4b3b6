// The compute terrain rasteriser's shared layout (render/terrain_raster_pass.h): set 3,
// bindings 5–10, beside the geometry of terrain_geometry.glsl (1–3) and the colour target (4).
//
// A triangle after setup (terrain_bin.comp) is a RasterTriangle: its screen vertices snapped to
// 1/256 pixel, the plane of its reverse-Z depth over the screen, which triangle of the frame's
// index buffer it is, and the rectangle of 8 × 8-pixel tiles its bounds touch. A triangle
// clipped by the near plane becomes one or two of them, with the same triangle id.
//
// Coverage is decided per sample by three edge functions. Each edge is evaluated from its
// canonical end (the lower of its two screen vertices, x then y) along its canonical direction,
// so the two triangles that share an edge compute bit-identical values of opposite sign: a
// sample on one side belongs to exactly one of them, and a sample exactly on the edge goes to
// the one whose own direction along it passes the tie rule (dy > 0, or dy = 0 and dx < 0): no
// cracks and no double hits, as the hardware's fill rule promises.
#ifndef TERRAIN_RASTER_GLSL
#define TERRAIN_RASTER_GLSL

const uint kRasterTile = 8u;   // pixels per tile side; terrain_raster.comp's workgroup is one tile

struct RasterTriangle {
  vec4 v01;    // xy: vertex 0, zw: vertex 1 (pixels, y down)
  vec4 v2z;    // xy: vertex 2, z: depth at vertex 0, w: unused
  vec4 plane;  // x: d depth / dx, y: d depth / dy
  uvec4 info;  // x: 1 + triangle in the frame's index buffer, y: first tile (x | y << 16), z: last tile
};
layout(std430, set = 3, binding = 5) buffer RasterTriangles { RasterTriangle rasterTriangles[]; };
// [0] raster triangles, [1] tile entries wanted, [2] tile entries dropped (the lists' capacity
// was short), [3] triangles drawn (after culling and clipping, counted once per source triangle).
layout(std430, set = 3, binding = 6) buffer RasterCounters { uint rasterCounters[]; };
layout(std430, set = 3, binding = 7) buffer TileCounts { uint tileCount[]; };  // per tile
layout(std430, set = 3, binding = 8) buffer TileStarts { uint tileStart[]; };  // per tile
layout(std430, set = 3, binding = 9) buffer TileLists { uint tileList[]; };    // raster triangle indices
// Per pixel and sample ((y · width + x) · samples + s): the terrain's reverse-Z depth, 0 where
// no terrain is (sky). Read by the Hi-Z build and, through set 0, by the pass that writes them
// into the depth attachment (terrain_depth.frag).
layout(std430, set = 3, binding = 10) buffer TerrainDepthOut { float terrainDepthOut[]; };
// Per 8 × 8 tile: 1 where its pixels' samples differ in depth (an edge of the terrain against the
// sky or against itself farther away), else 0; written by the multisampled raster for every tile.
// Only these tiles have their depth written per sample (render/terrain_depth_handover.h); every
// other pixel's samples get one depth from one fragment per pixel (terrain_depth_pixel.frag).
layout(std430, set = 3, binding = 11) writeonly buffer TileEdges { uint tileEdge[]; };
// A pixel is an edge when its samples' reverse-Z depths (∝ 1 / distance) differ by more than this
// share, or some are sky and some not. Elsewhere one depth serves the pixel: off by no more than
// the terrain's own depth range across that pixel, and less than 5 % of the distance.
const float kDepthEdgeShare = 0.05;

// One edge, canonical: E(p) = a · (p.x − base.x) + b · (p.y − base.y), times `sign` for the
// triangle's own direction; `tie`: whether a sample exactly on it is inside.
struct RasterEdge {
  vec2 base;
  vec2 ab;
  float sign;
  bool tie;
};

RasterEdge rasterEdge(vec2 from, vec2 to) {
  bool canonical = from.x < to.x || (from.x == to.x && from.y < to.y);
  vec2 lo = canonical ? from : to, hi = canonical ? to : from;
  RasterEdge e;
  e.base = lo;
  e.ab = vec2(lo.y - hi.y, hi.x - lo.x);
  e.sign = canonical ? 1.0 : -1.0;
  vec2 d = to - from;
  e.tie = d.y > 0.0 || (d.y == 0.0 && d.x < 0.0);
  return e;
}

// The edge function at p, the sign of the triangle's own direction applied (inside: > 0).
float edgeAt(RasterEdge e, vec2 p) {
  precise float v = e.ab.x * (p.x - e.base.x) + e.ab.y * (p.y - e.base.y);
  return e.sign * v;
}

bool insideEdge(RasterEdge e, vec2 p) {
  float v = edgeAt(e, p);
  return v > 0.0 || (v == 0.0 && e.tie);
}

// Whether the triangle's edge can have samples inside it in the pixel rectangle [lo, hi]: the
// edge function's largest value over the rectangle (at the corner its gradient points to),
// with a little slack for rounding (binning is conservative; the raster decides exactly).
bool edgeReaches(RasterEdge e, vec2 lo, vec2 hi) {
  vec2 g = e.ab * e.sign;
  vec2 corner = vec2(g.x > 0.0 ? hi.x : lo.x, g.y > 0.0 ? hi.y : lo.y);
  float v = edgeAt(e, corner);
  return v >= -1e-3 * (abs(g.x) + abs(g.y));
}

uvec2 unpackTile(uint t) { return uvec2(t & 0xffffu, t >> 16); }

#endif
