#version 450
#extension GL_GOOGLE_include_directive : require
// The interaction field's step (issue 19; render/simulation_pass.h): one thread per texel of the
// 1024 × 1024 toroidal window (32 × 32 tiles of 32 × 32, tile-major so a tile is one contiguous range
// for the trail store's copies). Each texel recovers (linearly, plus what a tile restored from the
// trail store missed while it was away) and takes every collider's press
// (simulation/shared/blade_response.glsl interactionStep).
layout(local_size_x = 8, local_size_y = 8) in;
#include "simulation_block.glsl"
layout(set = 1, binding = 2, std430) buffer Field { vec4 texels[]; };

void main() {
  ivec2 at = ivec2(gl_GlobalInvocationID.xy);  // window position: tile (at >> 5), texel (at & 31)
  ivec2 origin = sim.fieldTexels.zw;
  ivec2 tile = origin + (((at >> 5) - origin) & (kFieldWindowTiles - 1));  // the world tile held there
  ivec2 texel = tile * kFieldTileTexels + (at & 31);
  int windowTile = (at.x >> 5) + (at.y >> 5) * kFieldWindowTiles;
  uint index = uint(windowTile * kFieldTileTexels * kFieldTileTexels + (at.y & 31) * kFieldTileTexels + (at.x & 31));
  vec2 rel = (vec2(texel - sim.fieldTexels.xy) + 0.5) * kFieldCellM - sim.field.xy;
  float extra = sim.restoredDecay[windowTile >> 2][windowTile & 3];
  texels[index] = interactionStep(texels[index], rel, extra);
}
