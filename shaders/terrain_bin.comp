#version 450
#extension GL_GOOGLE_include_directive : require
// The compute terrain rasteriser's binning (render/terrain_raster_pass.h), two phases of one
// shader (push counts.z):
// 0 — setup: one thread per triangle of the frame's index buffer: to clip space, culled as the
//     hardware pipeline culls (outside the frustum, back-facing, no area), clipped by the near
//     plane into one or two raster triangles, which are appended with their tile rectangles;
//     each tile they may touch counts them.
// 1 — fill: one thread per raster triangle: after terrain_bin_scan.comp gave each tile its start,
//     the triangle is written into the list of every tile it may touch (the same tiles as counted).
// A triangle touching more than a few tiles (the large ones near the camera) is not walked by its
// own thread: the whole workgroup takes its tiles, so a few big triangles do not keep one thread
// busy while the rest wait.
#include "frame_uniforms.glsl"
#include "terrain_geometry.glsl"
#include "terrain_raster.glsl"

layout(local_size_x = 64) in;

const uint kOwnTiles = 4u;  // a triangle touching more tiles is walked by the workgroup
shared uint bigList[128];   // 64 threads × at most 2 raster triangles each
shared RasterTriangle bigTriangles[128];  // theirs, for the other threads (no buffer round trip)
shared uint bigCount;

vec4 clipPosition(uint v, Piece pc) {
  return frame.viewProj * vec4(vertexPosition(v) + pc.originFromCamera.xyz, 1.0);
}

uvec2 tileRect(RasterTriangle t, out uvec2 first) {
  first = unpackTile(t.info.y);
  return unpackTile(t.info.z) - first + 1u;
}

// Tile k of raster triangle r's rectangle, if the triangle may have samples in it: counted
// (phase 0) or listed (phase 1).
void visitTile(RasterTriangle t, uint r, uint k) {
  uvec2 first;
  uvec2 size = tileRect(t, first);
  uvec2 tile = first + uvec2(k % size.x, k / size.x);
  vec2 lo = vec2(tile * kRasterTile), hi = min(lo + float(kRasterTile), frame.viewport.xy);
  if (!edgeReaches(rasterEdge(t.v01.xy, t.v01.zw), lo, hi) || !edgeReaches(rasterEdge(t.v01.zw, t.v2z.xy), lo, hi) ||
      !edgeReaches(rasterEdge(t.v2z.xy, t.v01.xy), lo, hi))
    return;
  uint index = tile.y * shade.tiles.x + tile.x;
  if (shade.counts.z == 0u) {
    atomicAdd(tileCount[index], 1u);
  } else {
    uint at = tileStart[index] + atomicAdd(tileCount[index], 1u);
    if (at < shade.counts.w)
      tileList[at] = r;
    else
      atomicAdd(rasterCounters[2], 1u);  // the scan counted what the lists would need
  }
}

// Its tiles now if few, else queued for the workgroup.
void visitOrQueue(RasterTriangle t, uint r) {
  uvec2 first;
  uvec2 size = tileRect(t, first);
  uint n = size.x * size.y;
  if (n <= kOwnTiles) {
    for (uint k = 0u; k < n; ++k) visitTile(t, r, k);
  } else {
    uint q = atomicAdd(bigCount, 1u);
    bigList[q] = r;
    bigTriangles[q] = t;
  }
}

// Appends the raster triangle (s0, s1, s2) with depths z, front-facing, clockwise on screen
// (cross < 0, Vulkan's counter-clockwise with y down), if it covers any pixel.
void emit(uint tri, vec2 s0, vec2 s1, vec2 s2, vec3 z) {
  vec2 e1 = s1 - s0, e2 = s2 - s0;
  float cross = e1.x * e2.y - e1.y * e2.x;
  if (!(cross < 0.0)) return;  // back-facing (the pipeline culls them) or no area
  // Counter-clockwise in these coordinates, so the inside is where every edge function is > 0.
  vec2 t = s1; s1 = s2; s2 = t;
  float tz = z.y; z.y = z.z; z.z = tz;
  e1 = s1 - s0; e2 = s2 - s0;
  float det = -cross;
  vec2 lo = min(s0, min(s1, s2)), hi = max(s0, max(s1, s2));
  ivec2 size = ivec2(frame.viewport.xy);
  ivec2 p0 = max(ivec2(floor(lo)), ivec2(0)), p1 = min(ivec2(floor(hi)), size - 1);
  if (p0.x > p1.x || p0.y > p1.y) return;  // off screen
  RasterTriangle r;
  r.v01 = vec4(s0, s1);
  r.v2z = vec4(s2, z.x, 0.0);
  float dz1 = z.y - z.x, dz2 = z.z - z.x;
  r.plane = vec4((dz1 * e2.y - dz2 * e1.y) / det, (e1.x * dz2 - e2.x * dz1) / det, 0.0, 0.0);
  uvec2 t0 = uvec2(p0) / kRasterTile, t1 = uvec2(p1) / kRasterTile;
  r.info = uvec4(tri + 1u, t0.x | (t0.y << 16), t1.x | (t1.y << 16), 0u);
  uint at = atomicAdd(rasterCounters[0], 1u);
  rasterTriangles[at] = r;
  visitOrQueue(r, at);
}

vec2 snapped(vec2 p) { return round(p * 256.0) / 256.0; }

// Clip-space point → screen pixels (y down, as the viewport maps it), snapped to 1/256 pixel.
vec2 screenOf(vec4 c) { return snapped((c.xy / c.w * 0.5 + 0.5) * frame.viewport.xy); }

void setup(uint tri) {
  Piece pc = pieces[pieceOf(tri)];
  uvec3 v = triangleVertices(tri, pc);
  vec4 c[3] = vec4[3](clipPosition(v.x, pc), clipPosition(v.y, pc), clipPosition(v.z, pc));
  // Outside one plane of the frustum with every vertex: never drawn. Near: z ≤ w (reverse-Z),
  // far: z ≥ 0.
  bvec3 left = bvec3(c[0].x < -c[0].w, c[1].x < -c[1].w, c[2].x < -c[2].w);
  bvec3 right = bvec3(c[0].x > c[0].w, c[1].x > c[1].w, c[2].x > c[2].w);
  bvec3 top = bvec3(c[0].y < -c[0].w, c[1].y < -c[1].w, c[2].y < -c[2].w);
  bvec3 bottom = bvec3(c[0].y > c[0].w, c[1].y > c[1].w, c[2].y > c[2].w);
  bvec3 beyond = bvec3(c[0].z < 0.0, c[1].z < 0.0, c[2].z < 0.0);
  vec3 d = vec3(c[0].w - c[0].z, c[1].w - c[1].z, c[2].w - c[2].z);  // ≥ 0: behind the near plane
  if (all(left) || all(right) || all(top) || all(bottom) || all(beyond) || all(lessThan(d, vec3(0.0)))) return;
  // Sutherland–Hodgman against the near plane; a crossing is found from the lower vertex index
  // of its edge, so the two triangles sharing the edge find the same point.
  vec4 poly[4];
  uint n = 0u;
  uint ids[3] = uint[3](v.x, v.y, v.z);
  for (uint i = 0u; i < 3u; ++i) {
    uint j = (i + 1u) % 3u;
    if (d[i] >= 0.0) poly[n++] = c[i];
    if ((d[i] >= 0.0) != (d[j] >= 0.0)) {
      uint a = ids[i] < ids[j] ? i : j, b = ids[i] < ids[j] ? j : i;
      poly[n++] = mix(c[a], c[b], d[a] / (d[a] - d[b]));
    }
  }
  vec2 s0 = screenOf(poly[0]);
  float z0 = poly[0].z / poly[0].w;
  for (uint k = 1u; k + 1u < n; ++k)
    emit(tri, s0, screenOf(poly[k]), screenOf(poly[k + 1u]), vec3(z0, poly[k].z / poly[k].w, poly[k + 1u].z / poly[k + 1u].w));
}

void main() {
  if (gl_LocalInvocationIndex == 0u) bigCount = 0u;
  barrier();
  uint id = gl_GlobalInvocationID.x;
  if (shade.counts.z == 0u) {
    if (id < shade.counts.y) setup(id);
  } else if (id < rasterCounters[0]) {
    visitOrQueue(rasterTriangles[id], id);
  }
  barrier();
  uint big = bigCount;
  for (uint i = 0u; i < big; ++i) {
    RasterTriangle t = bigTriangles[i];
    uvec2 first;
    uvec2 size = tileRect(t, first);
    for (uint k = gl_LocalInvocationIndex; k < size.x * size.y; k += gl_WorkGroupSize.x) visitTile(t, bigList[i], k);
  }
}
