#version 450
#extension GL_GOOGLE_include_directive : require
// The compute terrain rasteriser's tile lists (render/terrain_raster_pass.h): one workgroup turns
// the tiles' counts (terrain_bin.comp, phase 0) into the start of each tile's list (an exclusive
// prefix sum) and zeroes the counts, which phase 1 counts up again as it fills the lists. The
// total the lists would need goes to rasterCounters[1].
#include "frame_uniforms.glsl"
#include "terrain_geometry.glsl"
#include "terrain_raster.glsl"

layout(local_size_x = 1024) in;
shared uint partial[1024];

void main() {
  uint tiles = shade.tiles.x * shade.tiles.y;
  uint per = (tiles + 1023u) / 1024u;
  uint first = gl_LocalInvocationIndex * per, last = min(first + per, tiles);
  uint sum = 0u;
  for (uint t = first; t < last; ++t) sum += tileCount[t];
  partial[gl_LocalInvocationIndex] = sum;
  barrier();
  // Hillis–Steele inclusive scan of the 1024 partial sums.
  for (uint step = 1u; step < 1024u; step <<= 1u) {
    uint add = gl_LocalInvocationIndex >= step ? partial[gl_LocalInvocationIndex - step] : 0u;
    barrier();
    partial[gl_LocalInvocationIndex] += add;
    barrier();
  }
  uint at = partial[gl_LocalInvocationIndex] - sum;
  for (uint t = first; t < last; ++t) {
    uint n = tileCount[t];
    tileStart[t] = at;
    tileCount[t] = 0u;
    at += n;
  }
  if (gl_LocalInvocationIndex == 1023u) rasterCounters[1] = partial[1023];
}
