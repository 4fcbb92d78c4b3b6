// The compute half of deferred terrain shading (render/terrain_shade_pass.h). The visibility
// pass left, per sample, 1 + the index of the triangle it sees, as four UNORM bytes, where its
// depth is not the far plane's 0 (elsewhere: sky, and the visibility target holds garbage). Here every pixel of
// the frame is shaded on the GPU's compute units: for each distinct triangle among its samples,
// the pixel-centre ray is intersected with that triangle, its attributes are interpolated with
// the resulting barycentrics (perspective-correct by construction: the intersection is in 3D),
// and shadeTerrain (terrain_shading.glsl, the same code as the forward fragment shader) gives
// its colour; samples that see no terrain get the sky colour of the sky pass. The colours are
// stored, sRGB-encoded, into the colour target itself (a storage view of it), so neither a
// full-screen sky pass nor a composite pass writes the multisampled target through the ROPs.
//
// The visibility target is read as a sampled image (texelFetch), not a storage image: sampled
// reads keep the GPU's colour compression of the multisampled target.
//
// Included by terrain_shade.comp (one sample per pixel) and terrain_shade_ms.comp (multisampled,
// VEGSTREAM_MULTISAMPLE defined). Sets: 0 frame, 1 imagery, 2 detail (as the terrain pass),
// 3 this pass's inputs.
#extension GL_GOOGLE_include_directive : require
#include "frame_uniforms.glsl"
#include "atmosphere.glsl"
#include "colour_score.glsl"
#include "terrain_detail.glsl"
#include "terrain_palette.glsl"
#include "terrain_shading.glsl"
#include "aov.glsl"

#ifndef VEGSTREAM_RASTER
layout(local_size_x = 8, local_size_y = 8) in;
#endif

#ifdef VEGSTREAM_RASTER  // terrain_raster.glsl: ids come from the compute rasteriser, not a target
#ifdef VEGSTREAM_MULTISAMPLE
layout(set = 3, binding = 4, r11f_g11f_b10f) uniform writeonly image2DMS target;
#define STORE_COLOUR(px, s, c) imageStore(target, px, s, aovGround(c))
const int kMaxSamples = 8;
#else
layout(set = 3, binding = 4, r11f_g11f_b10f) uniform writeonly image2D target;
#define STORE_COLOUR(px, s, c) imageStore(target, px, aovGround(c))
const int kMaxSamples = 1;
#endif
#else
#ifdef VEGSTREAM_MULTISAMPLE
layout(set = 3, binding = 0) uniform sampler2DMS visibility;
layout(set = 3, binding = 5) uniform sampler2DMS depthSamples;
layout(set = 3, binding = 4, r11f_g11f_b10f) uniform writeonly image2DMS target;
#define LOAD_ID(px, s) packUnorm4x8(texelFetch(visibility, px, s))
#define LOAD_DEPTH(px, s) texelFetch(depthSamples, px, s).r
#define STORE_COLOUR(px, s, c) imageStore(target, px, s, aovGround(c))
#define SAMPLES textureSamples(visibility)
const int kMaxSamples = 8;
#else
layout(set = 3, binding = 0) uniform sampler2D visibility;
layout(set = 3, binding = 5) uniform sampler2D depthSamples;
layout(set = 3, binding = 4, r11f_g11f_b10f) uniform writeonly image2D target;
#define LOAD_ID(px, s) packUnorm4x8(texelFetch(visibility, px, 0))
#define LOAD_DEPTH(px, s) texelFetch(depthSamples, px, 0).r
#define STORE_COLOUR(px, s, c) imageStore(target, px, aovGround(c))
#define SAMPLES 1
const int kMaxSamples = 1;
#endif

#endif

#include "terrain_geometry.glsl"

// Where the ray along `dir` meets the plane through p0 with normal n (camera-relative).
vec3 onPlane(vec3 dir, vec3 p0, vec3 n) {
  float denom = dot(n, dir);
  float t = abs(denom) > 1e-30 ? dot(n, p0) / denom : 0.0;
  return dir * t;
}

// Triangle `tri` as seen through the pixel centre (ray `dir`; the neighbours' rays for the
// derivatives), shaded.
vec3 shadeTriangle(uint tri, vec3 dir, vec3 dirX, vec3 dirY) {
  Piece pc = pieces[pieceOf(tri)];
  uint i0 = indexData[3u * tri] + pc.range.y, i1 = indexData[3u * tri + 1u] + pc.range.y,
       i2 = indexData[3u * tri + 2u] + pc.range.y;
  vec3 p0 = vertexPosition(i0) + pc.originFromCamera.xyz;
  vec3 e1 = vertexPosition(i1) + pc.originFromCamera.xyz - p0;
  vec3 e2 = vertexPosition(i2) + pc.originFromCamera.xyz - p0;
  vec3 n = cross(e1, e2);
  vec3 x = onPlane(dir, p0, n);
  // Barycentrics of x in the triangle's plane (extrapolated outside it, as a fragment at an
  // edge pixel's centre would be).
  vec3 q = x - p0;
  float d11 = dot(e1, e1), d12 = dot(e1, e2), d22 = dot(e2, e2);
  float q1 = dot(q, e1), q2 = dot(q, e2);
  float det = d11 * d22 - d12 * d12;
  float b1 = det != 0.0 ? (d22 * q1 - d12 * q2) / det : 0.0;
  float b2 = det != 0.0 ? (d11 * q2 - d12 * q1) / det : 0.0;
  vec3 b = vec3(1.0 - b1 - b2, b1, b2);
  TerrainPoint p;
  p.offset = x;
  p.normal = b.x * vertexNormal(i0) + b.y * vertexNormal(i1) + b.z * vertexNormal(i2);
  p.heightMsl = b.x * vertexHeight(i0) + b.y * vertexHeight(i1) + b.z * vertexHeight(i2);
  p.uv = b.x * vertexUv(i0) + b.y * vertexUv(i1) + b.z * vertexUv(i2);
  p.offsetDx = onPlane(dirX, p0, n) - x;
  p.offsetDy = onPlane(dirY, p0, n) - x;
  return shadeTerrain(p, TerrainImagery(pc.imageryUv, pc.previousUv, pc.layers));
}

// Shades pixel `px` whose samples see triangles 1 + ids[s] (0: sky), once per distinct id, and
// stores the colours into the target.
void shadePixel(ivec2 px, uint ids[kMaxSamples], int samples) {
  vec2 ndc = (vec2(px) + 0.5) * frame.viewport.zw * 2.0 - 1.0;
  vec3 dir = rayThrough(ndc);
  vec3 dirX = rayThrough(ndc + vec2(2.0 * frame.viewport.z, 0.0));
  vec3 dirY = rayThrough(ndc + vec2(0.0, 2.0 * frame.viewport.w));
  vec4 colours[kMaxSamples];
  for (int s = 0; s < samples; ++s) {
    int same = -1;  // an earlier sample that sees the same triangle (or sky): shade once per pixel
    for (int e = 0; e < s; ++e)
      if (same < 0 && ids[e] == ids[s]) same = e;
    if (same >= 0) {
      colours[s] = colours[same];
    } else {
      vec3 c = ids[s] == 0u ? ditheredSky(skyColor(normalize(dir)), uvec2(px)) : shadeTriangle(ids[s] - 1u, dir, dirX, dirY);
      colours[s] = vec4(min(c, vec3(65000.0)), 1.0);  // linear HDR (render_targets.h)
    }
    STORE_COLOUR(px, s, colours[s]);
  }
}

#ifndef VEGSTREAM_RASTER
void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (px.x >= int(frame.viewport.x) || px.y >= int(frame.viewport.y)) return;
  uint ids[kMaxSamples];
  int samples = min(SAMPLES, kMaxSamples);
  // The visibility target is not cleared (a full-screen multisampled clear costs as much as
  // drawing it on the H200): a sample the terrain did not reach kept the far depth, 0.
  for (int s = 0; s < samples; ++s) ids[s] = LOAD_DEPTH(px, s) > 0.0 ? LOAD_ID(px, s) : 0u;
  shadePixel(px, ids, samples);
}
#endif
