#ifndef SAMPLE_POSITIONS_GLSL
#define SAMPLE_POSITIONS_GLSL
// Vulkan's standard sample locations (spec "Multisampling", standardSampleLocations) for 1, 2, 4
// and 8 samples, within the pixel (0 … 1, y down). The compute terrain rasteriser
// (terrain_raster.glsl) samples its triangles there, so that the depth samples it writes into
// the depth attachment (terrain_depth.frag) are where the hardware tests the other passes'.
vec2 samplePosition(uint samples, uint s) {
  const vec2 two[2] = vec2[2](vec2(0.75, 0.75), vec2(0.25, 0.25));
  const vec2 four[4] = vec2[4](vec2(0.375, 0.125), vec2(0.875, 0.375), vec2(0.125, 0.625), vec2(0.625, 0.875));
  const vec2 eight[8] = vec2[8](vec2(0.5625, 0.3125), vec2(0.4375, 0.6875), vec2(0.8125, 0.5625),
                                vec2(0.3125, 0.1875), vec2(0.1875, 0.8125), vec2(0.0625, 0.4375),
                                vec2(0.6875, 0.9375), vec2(0.9375, 0.0625));
  if (samples == 2u) return two[s & 1u];
  if (samples == 4u) return four[s & 3u];
  if (samples == 8u) return eight[s & 7u];
  return vec2(0.5);
}
#endif
