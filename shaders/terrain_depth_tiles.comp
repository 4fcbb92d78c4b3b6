#version 450
#extension GL_GOOGLE_include_directive : require
// The terrain's depth hand-over, its list (render/terrain_depth_handover.h): one thread per row of
// 8 × 8-pixel tiles. A tile is wanted where a plant or a tree may be drawn (common/depth_tile_marks.glsl's
// cells, or all of them); the wanted tiles with a depth edge (the raster's flags) go to the edge
// list, written per sample, the others to runs along the row, written per pixel: a quad per run.
layout(local_size_x = 64) in;
#include "common/frame_uniforms.glsl"
#include "common/depth_tile_marks.glsl"

layout(std430, set = 1, binding = 0) readonly buffer TileEdges { uint tileEdge[]; };  // per tile: 1 at a depth edge
layout(std430, set = 1, binding = 1) buffer DepthSpans {
  uint spanCommand[4];  // VkDrawIndirectCommand: 6 vertices, a run per instance
  uvec4 spanTiles;      // x: the tiles the runs hold
  uvec4 spans[];        // first tile, one past the last, row
};
layout(std430, set = 1, binding = 2) buffer DepthEdges {
  uint edgeCommand[4];  // VkDrawIndirectCommand: 6 vertices, a tile per instance
  uint edgeTiles[];
};
layout(push_constant) uniform Push {
  uvec4 tiles;  // x, y: tiles across and down; z: samples per pixel; w: 1 = every tile wanted
} push;

const uint kTile = 8u;  // common/terrain_raster.glsl's kRasterTile

bool wanted(uint x, uint y) {
  if (push.tiles.w != 0u || markAll != 0u) return true;
  uvec2 fine = markGrid(kMarkFine), coarse = markGrid(kMarkCoarse);
  uvec2 f = uvec2(x, y) * kTile / kMarkFine, c = uvec2(x, y) * kTile / kMarkCoarse;
  return markCells[f.y * fine.x + f.x] != 0u || markCells[fine.x * fine.y + c.y * coarse.x + c.x] != 0u;
}

void closeRun(uint first, uint end, uint y) {
  if (end <= first) return;
  spans[atomicAdd(spanCommand[1], 1u)] = uvec4(first, end, y, 0u);
  atomicAdd(spanTiles.x, end - first);
}

void main() {
  uint y = gl_GlobalInvocationID.x;
  if (y >= push.tiles.y) return;
  uint first = 0u;  // the open run's first tile
  for (uint x = 0u; x < push.tiles.x; ++x) {
    bool edge = push.tiles.z > 1u && tileEdge[y * push.tiles.x + x] != 0u;
    bool pixel = wanted(x, y);
    if (pixel && edge) edgeTiles[atomicAdd(edgeCommand[1], 1u)] = y * push.tiles.x + x;
    if (!pixel || edge) {
      closeRun(first, x, y);
      first = x + 1u;
    }
  }
  closeRun(first, push.tiles.x, y);
}
