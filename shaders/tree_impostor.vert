#version 460
#extension GL_GOOGLE_include_directive : require
// Octahedral impostors of trees (issue 20, common/tree_impostor.glsl): a triangle per entry of
// the classify pass's impostor list, drawn in the basis of the captured view nearest the
// direction the tree is seen from, scaled and turned like the tree's model (tree.vert), its top
// swaying with the trunk's amplitude in the shared wind (the impostor moves as a whole). In the
// shadow pass the triangle stands across the sun itself, the nearest view's silhouette stretched
// over it (issue 39 item 8: a shadow as long as the sun makes it, render/README.md).
#include "common/frame_uniforms.glsl"
#include "common/simulation_block.glsl"
#include "simulation/shared/tree_bending.glsl"
#include "common/tree_layout.glsl"
#include "common/tree_push.glsl"
#include "common/tree_impostor.glsl"
#include "common/atmosphere.glsl"
#include "common/tree_shading.glsl"
#include "common/hiz_occlusion.glsl"

layout(location = 0) out vec3 vPos;
layout(location = 1) out vec2 vUv;  // in the atlas (0 … 1)
layout(location = 2) flat out uint vLayer;
layout(location = 3) flat out float vThreshold;
layout(location = 4) flat out uint vInstance;
// The tree's turn (treeRotation), its columns: the captured model-space normal into the world
// without the six sines and cosines per fragment.
layout(location = 5) flat out vec3 vRotX;
layout(location = 6) flat out vec3 vRotY;
layout(location = 7) flat out vec3 vTowards;  // the captured view's axis, world
// The captured colour's factor for this tree (treeImpostorFactor × its colour factor), per tree.
layout(location = 8) flat out vec3 vTint;
layout(location = 9) flat out vec3 vRotZ;
layout(location = 10) flat out vec4 vSky;   // the aerial perspective at the tree's centre
layout(location = 11) flat out float vSun;  // the sun shadow there
layout(location = 12) flat out vec4 vRect;  // the rectangle the model fills, in the atlas: centre, half extents

void main() {
  uvec4 entry = treeVisible[gl_InstanceIndex];
  TreeInstanceGpu t = treeInstances[entry.x];
  TreeModelGpu m = trees.models[push.model];
  uint seed = t.seed;
  vec2 scale = treeScale(t, m);
  float sxy = scale.x, sz = scale.y;
  vec3 root = t.position - trees.camera.xyz;
  vec3 centreRel = root + vec3(0.0, 0.0, m.shape.w * sz);
  // The direction the tree is seen from, in the model's frame; the nearest captured cell.
  // (The shadow pass: seen from the sun, so the cascade holds the silhouette the sun sees.)
  vec3 d = treeUnrotateYaw(push.mode == 1u ? frame.sunDirection.xyz : normalize(-centreRel), seed);
  uint g = trees.counts.w;
  vec2 cell = clamp(floor(treeImpostorUv(d) * float(g)), vec2(0.0), vec2(float(g) - 1.0));
  vec3 dc = treeImpostorDirection((cell + 0.5) / float(g));
  float r = m.shape.z;
  // The quad holds what the model covers seen along dc — a cylinder of the crown's radius and the
  // model's height about its centre — not the captured square: a side view of a tree is a third
  // as wide as it is tall (the H200 spent 26 ms a frame on the square's empty corners).
  float sinE = clamp(dc.z, 0.0, 1.0), cosE = sqrt(1.0 - sinE * sinE);
  float rc = 1.08 * m.shape.y, hh = 0.55 * m.shape.x;
  vec2 half_ = min(vec2(rc, hh * cosE + rc * sinE), vec2(r));
  // In the shadow pass the quad stands across the sun itself, not across the captured view
  // nearest it (cells are 10–20° apart): the captured silhouette stretched over the cylinder as
  // the sun sees it. Otherwise a shadow is as long as the nearest view's, not the sun's (a 15 m
  // conifer under a 35° sun cast 17 m instead of 21: tests/render/tree_shadow_test.cpp).
  vec3 seen = push.mode == 1u ? d : dc;
  vec3 right, up;
  treeImpostorBasis(seen, right, up);
  float sinS = clamp(seen.z, 0.0, 1.0), cosS = sqrt(1.0 - sinS * sinS);
  vec2 extent = min(vec2(rc, hh * cosS + rc * sinS), vec2(r));
  // Drawn on one triangle that holds the model (render/tree_impostor_outline.h): the H200's
  // graphics units are bound by primitives here, and a conifer fills a triangle better than a
  // rectangle. Apex (0, a), base (±b, 0) in the rectangle's units (up: 0 at its bottom … 1 at its
  // top); the fragment stage drops what lies outside the rectangle, as before.
  int bin = min(int(sinE * 4.0), 3);
  float apex = m.triangleApex[bin], base = m.triangleBase[bin];
  vec2 c = gl_VertexIndex % 3 == 2 ? vec2(0.0, 2.0 * apex - 1.0) : vec2(gl_VertexIndex % 3 == 0 ? -base : base, -1.0);
  vec3 modelPoint = vec3(0.0, 0.0, m.shape.w) + right * (c.x * extent.x) + up * (c.y * extent.y);
  // Sway: the trunk's bend at this height.
  vec3 wind = treeUnrotateYaw(vec3(uintBitsToFloat(entry.z), uintBitsToFloat(entry.w), 0.0), seed);
  if (dot(wind, wind) > 1e-6) {
    TreeBranchGpu trunk = treeBranches[m.mesh0.w];
    vec2 amp = branchAmplitude(wind, trunk.rC4.xyz, trunk.sFrequency.xyz, trunk.link.w, trunk.sFrequency.w,
                               float(seed & 1023u) * 0.00614, treeTime());
    float x = clamp(modelPoint.z / trunk.originLength.w, 0.0, 1.0);
    modelPoint += branchOffset(trunk.tC2.xyz, trunk.rC4.xyz, trunk.sFrequency.xyz, trunk.originLength.w, trunk.tC2.w,
                               trunk.rC4.w, x, amp);
  }
  mat3 rotation = treeRotation(seed);
  vec3 rel = root + rotation * vec3(modelPoint.xy * sxy, modelPoint.z * sz);
  vPos = rel;
  vUv = (cell + 0.5 + 0.5 * vec2(c.x * half_.x, -c.y * half_.y) / r) / float(g);
  vRect = vec4((cell + 0.5) / float(g), 0.5 * half_ / (r * float(g)));
  vLayer = m.mesh1.w;
  vThreshold = uintBitsToFloat(entry.y);
  vInstance = entry.x;
  vRotX = rotation[0];
  vRotY = rotation[1];
  vRotZ = rotation[2];
  vTowards = rotation * dc;
  vec4 ground = treeInstanceColour(t.colour);
  vTint = treeImpostorFactor(m.leaf.rgb, ground.rgb) * ground.a;
  vSky = treeVertexAtmosphere(centreRel);
  // The shadow of other trees: looked up just outside this one's crown, towards the sun (its own
  // centre is always in its own shadow).
  vec3 sunward = centreRel + frame.sunDirection.xyz * (0.6 * max(t.heightM, t.crownM));
  vSun = push.mode == 0u ? sunShadow(sunward, vec3(0.0, 0.0, 1.0)) : 1.0;
  gl_Position = (push.mode == 1u ? treeShadowMatrix(0u) : frame.viewProj) * vec4(rel, 1.0);
  // In colour, an impostor behind the terrain is dropped here, before any of its fragments: the
  // quad's sphere (its half extents, scaled, plus the sway) against this frame's Hi-Z pyramid.
  // Every vertex of the quad decides alike, so the quad goes whole. (The shadow pass keeps it.)
  float reach = length(extent) * max(sxy, sz) + 0.1 * t.heightM;
  if (push.mode == 0u && hiddenByTerrain(centreRel, reach)) gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
}
