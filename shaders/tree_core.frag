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
#include "common/tree_push.glsl"
#include "common/tree_shading.glsl"

layout(location = 0) in vec3 vPos;
layout(location = 1) in vec3 vNormal;
layout(location = 2) in vec2 vUv;
layout(location = 3) flat in uint vKind;
layout(location = 4) flat in float vThreshold;
layout(location = 5) flat in uint vInstance;
layout(location = 6) in float vOcclusion;
layout(location = 7) flat in float vTint;
layout(location = 8) in vec2 vCell;
layout(location = 9) in vec4 vSky;
layout(location = 10) in float vSun;
layout(location = 0) out vec4 outColor;

void main() {
  TreeModelGpu m = trees.models[push.model];
  vec3 lit = treeLight(normalize(vNormal), m.leaf.rgb * vTint * kTreeCoreShade, m.leaf.w, false, vOcclusion, vSun);
  outColor = vec4(mix(vSky.rgb, lit, vSky.a), 1.0);
}
