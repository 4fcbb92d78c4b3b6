// Where a camera-relative point falls in the simulation's world-aligned toroidal grids
// (simulation_layout.glsl): GLSL for the plants (shaders/common/simulation_fields.glsl), C++ for the
// tests that read the grids back (simulation/shared_code.h). Needs the simulation block `sim`.

// Where a camera-relative point's wind cell lives in the wind grid's buffer (−1: outside the
// window), and the world cell itself.
VS_INLINE ivec2 windCellOf(VS_SIM_ARG vec3 p) {
  vec2 q = (vec2(sim.windCamera.x, sim.windCamera.y) + vec2(p.x, p.y)) * (1.0f / kWindCellM);
  return ivec2(sim.windCells.x, sim.windCells.y) + ivec2(int(floor(q.x)), int(floor(q.y)));
}

VS_INLINE int windCellIndex(VS_SIM_ARG ivec2 cell) {
  ivec2 off = cell - ivec2(sim.windCells.z, sim.windCells.w);
  if (off.x < 0 || off.y < 0 || off.x >= kWindGrid || off.y >= kWindGrid) return -1;
  return (cell.x & (kWindGrid - 1)) + (cell.y & (kWindGrid - 1)) * kWindGrid;
}

// Where the interaction texel under a camera-relative point lives in the field's buffer (tile-major:
// tile (x mod 16, y mod 16), then the texel in the tile); −1 outside the window.
VS_INLINE int fieldTexelIndex(VS_SIM_ARG vec3 p) {
  vec2 q = (vec2(sim.field.x, sim.field.y) + vec2(p.x, p.y)) * (1.0f / kFieldCellM);
  ivec2 texel = ivec2(sim.fieldTexels.x, sim.fieldTexels.y) + ivec2(int(floor(q.x)), int(floor(q.y)));
  ivec2 tile = ivec2(texel.x >> 5, texel.y >> 5);  // kFieldTileTexels = 32; arithmetic shift: floor
  ivec2 off = tile - ivec2(sim.fieldTexels.z, sim.fieldTexels.w);
  if (off.x < 0 || off.y < 0 || off.x >= kFieldWindowTiles || off.y >= kFieldWindowTiles) return -1;
  int windowTile = (tile.x & (kFieldWindowTiles - 1)) + (tile.y & (kFieldWindowTiles - 1)) * kFieldWindowTiles;
  return windowTile * kFieldTileTexels * kFieldTileTexels + (texel.y & 31) * kFieldTileTexels + (texel.x & 31);
}
