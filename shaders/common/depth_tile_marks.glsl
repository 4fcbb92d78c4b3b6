#ifndef DEPTH_TILE_MARKS_GLSL
#define DEPTH_TILE_MARKS_GLSL
// Where this frame's plants and trees may put a fragment (render/terrain_depth_handover.h): the
// screen cells that the terrain's depth must be written into before they are drawn, because only
// there is anything depth-tested against it. The tree classify marks every tree it appends (its
// sphere), the Hi-Z cull every seed triangle whose plants may show (its plants' box and their
// shadows' box, the same boxes it tests); terrain_depth_tiles.comp then lists the 8 × 8 tiles
// under marked cells. A mark is conservative: a rectangle grown by 2 pixels, cells of 16 pixels,
// or cells of 128 pixels when the rectangle spans more than 64 small ones; anything that reaches
// the near plane marks what lies in front of it. Needs frame_uniforms.glsl; marks only when
// frame.terrainDepth.w is 1 (the terrain rasterised in compute: elsewhere binding 10 is a
// placeholder).

layout(std430, set = 0, binding = 10) buffer DepthTileMarks {
  uint markAll;      // 1: every cell is marked
  uint markCells[];  // the 16-pixel cells row by row, then the 128-pixel cells row by row
};

const uint kMarkFine = 16u, kMarkCoarse = 128u;
const uint kMarkFineMost = 64u;  // small cells a rectangle may mark one by one

uvec2 markGrid(uint cell) { return (uvec2(frame.viewport.xy) + cell - 1u) / cell; }

// Marks the cells under the pixel rectangle [lo, hi] (pixels, y down).
void markRect(vec2 lo, vec2 hi) {
  vec2 last = frame.viewport.xy - 1.0;
  lo = max(lo - 2.0, vec2(0.0));
  hi = min(hi + 2.0, last);
  if (lo.x > hi.x || lo.y > hi.y) return;  // off screen
  uvec2 f0 = uvec2(lo) / kMarkFine, f1 = uvec2(hi) / kMarkFine;
  uvec2 fine = markGrid(kMarkFine);
  if ((f1.x - f0.x + 1u) * (f1.y - f0.y + 1u) <= kMarkFineMost) {
    for (uint y = f0.y; y <= f1.y; ++y)
      for (uint x = f0.x; x <= f1.x; ++x) markCells[y * fine.x + x] = 1u;
    return;
  }
  uvec2 c0 = uvec2(lo) / kMarkCoarse, c1 = uvec2(hi) / kMarkCoarse;
  uint base = fine.x * fine.y, w = markGrid(kMarkCoarse).x;
  for (uint y = c0.y; y <= c1.y; ++y)
    for (uint x = c0.x; x <= c1.x; ++x) markCells[base + y * w + x] = 1u;
}

// Marks every cell.
void markEverything() {
  if (frame.terrainDepth.w != 0.0) markAll = 1u;
}

// Adds clip-space point c (in front of the near plane) to the rectangle [pmin, pmax].
void markExtend(vec4 c, inout vec2 pmin, inout vec2 pmax) {
  vec2 px = (c.xy / c.w * 0.5 + 0.5) * frame.viewport.xy;
  pmin = min(pmin, px);
  pmax = max(pmax, px);
}

// Marks what the box [lo, hi] (camera-relative metres) covers on screen: the part of it in
// front of the near plane (reverse-Z: clip.z < clip.w), its corners there and where its edges
// cross the plane.
void markBox(vec3 lo, vec3 hi) {
  if (frame.terrainDepth.w == 0.0) return;
  vec4 c[8];
  for (int i = 0; i < 8; ++i)
    c[i] = frame.viewProj * vec4((i & 1) != 0 ? hi.x : lo.x, (i & 2) != 0 ? hi.y : lo.y, (i & 4) != 0 ? hi.z : lo.z, 1.0);
  vec2 pmin = vec2(1e30), pmax = vec2(-1e30);
  for (int i = 0; i < 8; ++i) {
    float di = c[i].w - c[i].z;
    if (di > 0.0 && c[i].w > 0.0) markExtend(c[i], pmin, pmax);
    for (int axis = 1; axis < 8; axis <<= 1) {  // the edges from corner i to a corner above it
      if ((i & axis) != 0) continue;
      float dj = c[i | axis].w - c[i | axis].z;
      if ((di > 0.0) == (dj > 0.0)) continue;
      vec4 p = mix(c[i], c[i | axis], di / (di - dj));
      if (p.w <= 0.0) {  // the plane's crossing behind the eye: cannot bound it
        markEverything();
        return;
      }
      markExtend(p, pmin, pmax);
    }
  }
  if (pmin.x <= pmax.x) markRect(pmin, pmax);  // else wholly behind the near plane
}

void markSphere(vec3 centre, float radius) { markBox(centre - radius, centre + radius); }

#endif
