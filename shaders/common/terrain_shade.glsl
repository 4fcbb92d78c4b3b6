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

layout(local_size_x = 8, local_size_y = 8) in;

#ifdef VEGSTREAM_MULTISAMPLE
layout(set = 3, binding = 0) uniform sampler2DMS visibility;
layout(set = 3, binding = 5) uniform sampler2DMS depthSamples;
layout(set = 3, binding = 4, rgba8) uniform writeonly image2DMS target;
#define LOAD_ID(px, s) packUnorm4x8(texelFetch(visibility, px, s))
#define LOAD_DEPTH(px, s) texelFetch(depthSamples, px, s).r
#define STORE_COLOUR(px, s, c) imageStore(target, px, s, c)
#define SAMPLES textureSamples(visibility)
const int kMaxSamples = 8;
#else
layout(set = 3, binding = 0) uniform sampler2D visibility;
layout(set = 3, binding = 5) uniform sampler2D depthSamples;
layout(set = 3, binding = 4, rgba8) uniform writeonly image2D target;
#define LOAD_ID(px, s) packUnorm4x8(texelFetch(visibility, px, 0))
#define LOAD_DEPTH(px, s) texelFetch(depthSamples, px, 0).r
#define STORE_COLOUR(px, s, c) imageStore(target, px, c)
#define SAMPLES 1
const int kMaxSamples = 1;
#endif

// terrain::TerrainVertex (36 bytes: position, normal, heightMsl, uv), read as floats.
layout(std430, set = 3, binding = 1) readonly buffer Vertices { float vertexData[]; };
layout(std430, set = 3, binding = 2) readonly buffer Indices { uint indexData[]; };
// One per drawn piece, in draw order (mirrors TerrainPiece in render/terrain_pass.h).
struct Piece {
  vec4 originFromCamera;
  vec4 imageryUv;
  vec4 previousUv;
  vec4 layers;
  uvec4 range;  // x: first triangle, y: first vertex (the draw's vertex offset), z: triangles
};
layout(std430, set = 3, binding = 3) readonly buffer Pieces { Piece pieces[]; };
layout(push_constant) uniform ShadePush {
  uvec4 counts;  // x: pieces
} shade;

const int kVertexFloats = 9;

// A point on the ray from the camera (the origin) through `ndc`.
vec3 rayThrough(vec2 ndc) {
  vec4 p = frame.invViewProj * vec4(ndc, 0.5, 1.0);
  return p.xyz / p.w;
}

// The piece that holds triangle `tri`: pieces are in draw order with increasing first triangles.
uint pieceOf(uint tri) {
  uint lo = 0u, hi = shade.counts.x - 1u;
  while (lo < hi) {
    uint mid = (lo + hi + 1u) / 2u;
    if (pieces[mid].range.x <= tri) lo = mid; else hi = mid - 1u;
  }
  return lo;
}

vec3 vertexPosition(uint v) { return vec3(vertexData[v * kVertexFloats], vertexData[v * kVertexFloats + 1], vertexData[v * kVertexFloats + 2]); }
vec3 vertexNormal(uint v) { return vec3(vertexData[v * kVertexFloats + 3], vertexData[v * kVertexFloats + 4], vertexData[v * kVertexFloats + 5]); }
float vertexHeight(uint v) { return vertexData[v * kVertexFloats + 6]; }
vec2 vertexUv(uint v) { return vec2(vertexData[v * kVertexFloats + 7], vertexData[v * kVertexFloats + 8]); }

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

vec3 srgbFromLinear(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (px.x >= int(frame.viewport.x) || px.y >= int(frame.viewport.y)) return;
  vec2 ndc = (vec2(px) + 0.5) * frame.viewport.zw * 2.0 - 1.0;
  vec3 dir = rayThrough(ndc);
  vec3 dirX = rayThrough(ndc + vec2(2.0 * frame.viewport.z, 0.0));
  vec3 dirY = rayThrough(ndc + vec2(0.0, 2.0 * frame.viewport.w));
  uint ids[kMaxSamples];
  vec4 colours[kMaxSamples];
  int samples = min(SAMPLES, kMaxSamples);
  for (int s = 0; s < samples; ++s) {
    // The visibility target is not cleared (a full-screen multisampled clear costs as much as
    // drawing it on the H200): a sample the terrain did not reach kept the far depth, 0.
    ids[s] = LOAD_DEPTH(px, s) > 0.0 ? LOAD_ID(px, s) : 0u;
    int same = -1;  // an earlier sample that sees the same triangle (or sky): shade once per pixel
    for (int e = 0; e < s; ++e)
      if (same < 0 && ids[e] == ids[s]) same = e;
    if (same >= 0) {
      colours[s] = colours[same];
    } else {
      vec3 c = ids[s] == 0u ? skyColor(normalize(dir)) : shadeTriangle(ids[s] - 1u, dir, dirX, dirY);
      colours[s] = vec4(srgbFromLinear(c), 1.0);
    }
    STORE_COLOUR(px, s, colours[s]);
  }
}
