#version 460
#extension GL_GOOGLE_include_directive : require
// The crowns' opaque cores (vegetation/tree_core.h, issue 20): foliage deep in the crown, in its
// own shade — the leaf colour darkened by kTreeCoreShade — lit like the cards but never through
// the leaf. No alpha test and no discard, so the depth test and write come before the shader
// (early_fragment_tests): the cards drawn after the cores are rejected behind them unshaded. A
// core never cross-fades by dither (that would need a discard): the vertex shader shrinks it away
// instead while its level fades out (tree.vert).
layout(early_fragment_tests) in;
#include "common/frame_uniforms.glsl"
#include "common/atmosphere.glsl"
#include "common/tree_layout.glsl"
#include "common/aov.glsl"
#include "common/tree_push.glsl"
#include "common/tree_shading.glsl"

layout(location = 0) in vec3 vPos;
layout(location = 1) in vec3 vNormal;
layout(location = 2) in vec2 vUv;
layout(location = 3) flat in uint vKind;
layout(location = 4) flat in float vThreshold;
layout(location = 5) flat in uint vInstance;
layout(location = 6) in float vOcclusion;
layout(location = 7) flat in vec4 vColour;
layout(location = 8) in vec2 vCell;
layout(location = 9) in vec4 vSky;
layout(location = 10) in float vSun;
layout(location = 0) out vec4 outColor;

// Value noise over the core's surface, about 40 cm clumps in the tree's frame (vUv carries no
// pattern for a core): sprays half in shade, so the solid does not read as a smooth surface.
// An integer hash of the lattice point (pcg3d, Jarzynski & Olano 2020): no sine per corner, eight
// corners a fragment.
float coreHash(vec3 c) {
  uvec3 v = uvec3(ivec3(c)) * 1664525u + 1013904223u;
  v.x += v.y * v.z; v.y += v.z * v.x; v.z += v.x * v.y;
  v ^= v >> 16u;
  v.x += v.y * v.z;
  return float(v.x >> 8) * (1.0 / 16777216.0);
}
float coreNoise(vec3 p) {
  vec3 i = floor(p), f = fract(p);
  f = f * f * (3.0 - 2.0 * f);
  float n = 0.0;
  for (int k = 0; k < 8; ++k) {
    vec3 o = vec3(k & 1, (k >> 1) & 1, (k >> 2) & 1);
    vec3 w = mix(1.0 - f, f, o);
    n += coreHash(i + o) * w.x * w.y * w.z;
  }
  return n;
}

void main() {
  TreeModelGpu m = trees.models[push.model];
  float clumps = mix(0.6, 1.25, coreNoise((vPos + trees.camera.xyz) * 2.5));
  vec3 albedo = vColour.rgb * vColour.a * kTreeCoreShade * clumps;
  vec3 lit = treeLight(normalize(vNormal), albedo, m.leaf.w, false, vOcclusion, vSun);
  outColor = aovFrame() ? aovVegetation(m.ids.x) : vec4(lit * vSky.a + vSky.rgb, 1.0);
}
