#version 450
#extension GL_GOOGLE_include_directive : require
// The terrain's depth hand-over, its list (render/terrain_depth_handover.h): a workgroup per row of
// 8 × 8-pixel tiles, a thread per tile. A tile is wanted where a plant or a tree may be drawn
// (common/depth_tile_marks.glsl's cells, or all of them); the wanted tiles with a depth edge (the
// raster's flags) go to the edge list, written per sample, the others to runs along the row,
// written per pixel: a quad per run, appended by the thread of its first tile. The last row to
// finish decides: where the wanted tiles are nearly all of them, one full-screen triangle replaces
// the runs, as it costs less than the runs of the whole screen (render/terrain_depth_handover.h).
layout(local_size_x = 256) in;
#include "common/frame_uniforms.glsl"
#include "common/depth_tile_marks.glsl"

layout(std430, set = 1, binding = 0) readonly buffer TileEdges { uint tileEdge[]; };  // per tile: 1 at a depth edge
layout(std430, set = 1, binding = 1) buffer DepthSpans {
  uint spanCommand[4];  // VkDrawIndirectCommand: 6 vertices, a run per instance
  uint fullCommand[4];  // VkDrawIndirectCommand: a full-screen triangle, instance count 0 or 1
  uvec4 spanTiles;      // x: the tiles written per pixel; y: the rows listed so far
  uvec4 spans[];        // first tile, one past the last, row
};
layout(std430, set = 1, binding = 2) buffer DepthEdges {
  uint edgeCommand[4];  // VkDrawIndirectCommand: 6 vertices, a tile per instance
  uint edgeTiles[];
};
layout(push_constant) uniform Push {
  uvec4 tiles;  // x, y: tiles across and down; z: samples per pixel; w: 1 = every tile wanted
  uvec4 full;   // x: the share of the tiles (%) from which one full-screen triangle replaces the runs
} push;

const uint kTile = 8u;  // common/terrain_raster.glsl's kRasterTile

bool wanted(uint x, uint y) {
  if (push.tiles.w != 0u || markAll != 0u) return true;
  uvec2 fine = markGrid(kMarkFine), coarse = markGrid(kMarkCoarse);
  uvec2 f = uvec2(x, y) * kTile / kMarkFine, c = uvec2(x, y) * kTile / kMarkCoarse;
  return markCells[f.y * fine.x + f.x] != 0u || markCells[fine.x * fine.y + c.y * coarse.x + c.x] != 0u;
}

const uint kRowMost = 1024u;  // tiles of a row in shared memory (8192 pixels); past them, a run per tile
shared uint sPixel[kRowMost];  // 1: the tile is written per pixel

void appendRun(uint first, uint end, uint y) {
  spans[atomicAdd(spanCommand[1], 1u)] = uvec4(first, end, y, 0u);
  atomicAdd(spanTiles.x, end - first);
}

// The last row listed: one full-screen triangle (per pixel, the edge tiles per sample after it)
// when the runs and edges hold at least push.full.x % of the tiles. Atomics read what the other
// workgroups added.
void chooseFull() {
  uint total = push.tiles.x * push.tiles.y, edges = atomicAdd(edgeCommand[1], 0u);
  if ((atomicAdd(spanTiles.x, 0u) + edges) * 100u < total * push.full.x) return;
  spanCommand[1] = 0u;
  fullCommand[1] = 1u;
  spanTiles.x = total - edges;
}

shared bool sLast;

void main() {
  uint y = gl_WorkGroupID.x;
  for (uint x = gl_LocalInvocationID.x; x < push.tiles.x; x += gl_WorkGroupSize.x) {
    bool edge = push.tiles.z > 1u && tileEdge[y * push.tiles.x + x] != 0u;
    bool want = wanted(x, y);
    if (want && edge) edgeTiles[atomicAdd(edgeCommand[1], 1u)] = y * push.tiles.x + x;
    if (x < kRowMost)
      sPixel[x] = want && !edge ? 1u : 0u;
    else if (want && !edge)
      appendRun(x, x + 1u, y);
  }
  barrier();
  uint row = min(push.tiles.x, kRowMost);
  for (uint x = gl_LocalInvocationID.x; x < row; x += gl_WorkGroupSize.x) {
    if (sPixel[x] == 0u || (x > 0u && sPixel[x - 1u] != 0u)) continue;  // not a run's first tile
    uint end = x + 1u;
    while (end < row && sPixel[end] != 0u) ++end;
    appendRun(x, end, y);
  }
  memoryBarrierBuffer();
  barrier();
  if (gl_LocalInvocationIndex == 0u) sLast = atomicAdd(spanTiles.y, 1u) == push.tiles.y - 1u;
  barrier();
  if (sLast && gl_LocalInvocationIndex == 0u) chooseFull();
}
