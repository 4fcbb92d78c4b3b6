// The compute terrain rasteriser's last dispatch (render/terrain_raster_pass.h): one workgroup
// per 8 × 8-pixel tile, one thread per pixel. The tile's raster triangles (terrain_bin.comp's
// lists) are taken 64 at a time into shared memory; each thread keeps, per sample, the nearest
// (reverse-Z: largest) depth and its triangle (ties: the lower triangle, whatever order the list
// holds them in, so the frame is deterministic). Then the depths go out for the Hi-Z build and
// the fragments drawn over the terrain, and the pixel is shaded exactly as the deferred shade
// shades it (terrain_shade.glsl's shadePixel: the same ids give the same colours).
//
// Included by terrain_raster.comp (one sample per pixel) and terrain_raster_ms.comp
// (VEGSTREAM_MULTISAMPLE). Sets as terrain_shade.glsl.
#extension GL_GOOGLE_include_directive : require
#define VEGSTREAM_RASTER 1
#include "terrain_shade.glsl"
#include "terrain_raster.glsl"
#include "sample_positions.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

const uint kBatch = 64u;   // raster triangles in shared memory at a time: one per thread
// Per triangle: its three edges (base xy, gradient xy), their signs and tie rules, the depth
// plane (vertex 0's position and depth, d/dx, d/dy) and its id.
shared vec4 sEdge[3][kBatch];
shared vec4 sSigns[kBatch];  // xyz: signs, w: tie bits (as float: 0 … 7)
shared vec4 sPlane[kBatch];  // xy: vertex 0, z: its depth, w: unused
shared vec4 sSlope[kBatch];  // xy: d depth / dx, dy; z: id (uint bits)
shared vec4 sBounds[kBatch];  // the triangle's screen bounds: xy lowest, zw highest (pixels)

void loadTriangle(uint slot, RasterTriangle t) {
  RasterEdge e[3] = RasterEdge[3](rasterEdge(t.v01.xy, t.v01.zw), rasterEdge(t.v01.zw, t.v2z.xy),
                                  rasterEdge(t.v2z.xy, t.v01.xy));
  uint ties = 0u;
  for (int k = 0; k < 3; ++k) {
    sEdge[k][slot] = vec4(e[k].base, e[k].ab);
    if (e[k].tie) ties |= 1u << k;
  }
  sSigns[slot] = vec4(e[0].sign, e[1].sign, e[2].sign, float(ties));
  sPlane[slot] = vec4(t.v01.xy, t.v2z.z, 0.0);
  sSlope[slot] = vec4(t.plane.xy, uintBitsToFloat(t.info.x), 0.0);
  sBounds[slot] = vec4(min(t.v01.xy, min(t.v01.zw, t.v2z.xy)), max(t.v01.xy, max(t.v01.zw, t.v2z.xy)));
}

// Triangle `slot`'s edges from shared memory, once per pixel (not per sample).
void storedEdges(uint slot, out RasterEdge e[3]) {
  vec4 signs = sSigns[slot];
  uint ties = uint(signs.w);
  for (int k = 0; k < 3; ++k) {
    vec4 ed = sEdge[k][slot];
    e[k].base = ed.xy;
    e[k].ab = ed.zw;
    e[k].sign = signs[k];
    e[k].tie = (ties & (1u << k)) != 0u;
  }
}

#ifdef VEGSTREAM_MULTISAMPLE
shared uint sDepthEdge;  // whether a pixel of the tile is a depth edge (kDepthEdgeShare)

// Whether the pixel's samples hold depths too far apart to share one (or sky beside terrain).
bool depthEdge(float best[kMaxSamples], int samples) {
  float lo = best[0], hi = best[0];
  for (int s = 1; s < kMaxSamples; ++s) {
    if (s >= samples) break;
    lo = min(lo, best[s]);
    hi = max(hi, best[s]);
  }
  return lo == 0.0 ? hi > 0.0 : hi > lo * (1.0 + kDepthEdgeShare);
}
#endif

void main() {
#ifdef VEGSTREAM_MULTISAMPLE  // one sample per pixel has no depth edges within a pixel
  if (gl_LocalInvocationIndex == 0u) sDepthEdge = 0u;
  barrier();
#endif
  uvec2 tile = gl_WorkGroupID.xy;
  uint tileIndex = tile.y * shade.tiles.x + tile.x;
  ivec2 px = ivec2(tile * kRasterTile + gl_LocalInvocationID.xy);
  bool onScreen = px.x < int(frame.viewport.x) && px.y < int(frame.viewport.y);
  int samples = min(int(shade.tiles.z), kMaxSamples);
  uint start = tileStart[tileIndex];
  uint capacity = shade.counts.w;
  uint n = start < capacity ? min(tileCount[tileIndex], capacity - start) : 0u;

  float best[kMaxSamples];
  uint ids[kMaxSamples];
  for (int s = 0; s < kMaxSamples; ++s) {
    best[s] = 0.0;  // the far plane: sky
    ids[s] = 0u;
  }
  for (uint b = 0u; b < n; b += kBatch) {
    uint k = b + gl_LocalInvocationIndex;
    if (k < n) loadTriangle(gl_LocalInvocationIndex, rasterTriangles[tileList[start + k]]);
    barrier();
    uint m = min(kBatch, n - b);
    if (onScreen) {
      vec2 lo = vec2(px), hi = lo + 1.0;
      for (uint j = 0u; j < m; ++j) {
        // Most of a tile's triangles miss most of its pixels: one bounds test rejects them.
        vec4 bounds = sBounds[j];
        if (bounds.x >= hi.x || bounds.y >= hi.y || bounds.z < lo.x || bounds.w < lo.y) continue;
        vec4 plane = sPlane[j], slope = sSlope[j];
        uint id = floatBitsToUint(slope.z);
        RasterEdge e[3];
        storedEdges(j, e);
        for (int s = 0; s < kMaxSamples; ++s) {
          if (s >= samples) break;
          vec2 p = vec2(px) + samplePosition(uint(samples), uint(s));
          if (!insideEdge(e[0], p) || !insideEdge(e[1], p) || !insideEdge(e[2], p)) continue;
          float z = plane.z + slope.x * (p.x - plane.x) + slope.y * (p.y - plane.y);
          if (z <= 0.0) continue;  // beyond the far plane
          if (z > best[s] || (z == best[s] && id < ids[s])) {
            best[s] = z;
            ids[s] = id;
          }
        }
      }
    }
    barrier();
  }
#ifdef VEGSTREAM_MULTISAMPLE
  if (onScreen && depthEdge(best, samples)) sDepthEdge = 1u;  // any writer: the same value
  barrier();
  if (gl_LocalInvocationIndex == 0u) tileEdge[tileIndex] = sDepthEdge;
#endif
  if (!onScreen) return;
  uint base = (uint(px.y) * uint(frame.viewport.x) + uint(px.x)) * uint(samples);
  for (int s = 0; s < samples; ++s) terrainDepthOut[base + uint(s)] = best[s];
  shadePixel(px, ids, samples);
}
