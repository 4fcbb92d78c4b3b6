#version 460
#extension GL_GOOGLE_include_directive : require
// Tree models (issue 20): one instance per visible-list entry of the tree classify pass. The
// vertex is bent through its branch hierarchy (seed 002 §4.3: every vertex carries its branch and
// its x along it; walking up to the trunk gives each ancestor's x), each branch by its fitted
// tapered-beam shape with the length correction (simulation/shared/tree_bending.glsl, 002 §4.4)
// at an amplitude from the shared wind filtered at its own resonance (002 §4.5), leaves flutter;
// positional animation only (002 §4.8's cheaper variant: the normals stay the undeformed ones).
// Per tree, from its seed: yaw, lean, a scale to its height and crown, and each branch turned by up
// to ±20° about the trunk — so no two trees of one model variant look alike.
// Modes (push): 0 colour, 2 impostor capture: the model as built, through push.capture, no tree
// and no wind (render/tree_impostors.h). (Trees cast shadows through their impostors only.)
#include "common/frame_uniforms.glsl"
#include "common/simulation_block.glsl"
#include "simulation/shared/tree_bending.glsl"
#include "common/tree_layout.glsl"
#include "common/tree_push.glsl"
#include "common/tree_impostor.glsl"
#include "common/atmosphere.glsl"
#include "common/tree_shading.glsl"

layout(location = 0) in vec3 inPosition;
layout(location = 1) in uint inBranch;
layout(location = 2) in vec3 inNormal;
layout(location = 3) in float inAlong;
layout(location = 4) in vec2 inUv;
layout(location = 5) in uint inKind;
layout(location = 6) in float inFlutter;

layout(location = 0) out vec3 vPos;
layout(location = 1) out vec3 vNormal;
layout(location = 2) out vec2 vUv;
layout(location = 3) flat out uint vKind;
layout(location = 4) flat out float vThreshold;
layout(location = 5) flat out uint vInstance;
layout(location = 6) out float vOcclusion;
layout(location = 7) flat out vec4 vColour;  // rgb: the leaves' albedo (treeLeafAlbedo: taken per tree, not per fragment), a: colour factor
layout(location = 8) out vec2 vCell;  // capture: the point in its cell's square (−1 … 1), outside is cut
layout(location = 9) out vec4 vSky;   // the aerial perspective: in-scattered light, transmittance
layout(location = 10) out float vSun; // the sun shadow

uint hashU(uint x) {  // lowbias32 (Wellons): branch angles and phases from the tree's seed
  x ^= x >> 16; x *= 0x7feb352du; x ^= x >> 15; x *= 0x846ca68bu; x ^= x >> 16;
  return x;
}
float hash01(uint x) { return float(hashU(x) >> 8) * (1.0 / 16777216.0); }

vec3 rotateAbout(vec3 v, vec3 axis, float angle) {
  float c = cos(angle), s = sin(angle);
  return v * c + cross(axis, v) * s + axis * dot(axis, v) * (1.0 - c);
}

void main() {
  TreeModelGpu m = trees.models[push.model];
  uint firstBranch = m.mesh0.w;
  vec3 p = inPosition;
  vec3 n = inNormal;
  vKind = inKind;
  vUv = inUv;
  vOcclusion = clamp(length(p.xy) / max(m.shape.y, 0.1), 0.0, 1.0) * 0.6 + clamp(p.z / m.shape.x, 0.0, 1.0) * 0.4;
  vCell = vec2(0.0);
  vSky = vec4(0.0, 0.0, 0.0, 1.0);
  vSun = 1.0;
  if (push.mode >= 2u) {  // impostor capture: instance i draws the model into cell i of the atlas
    uint g = push.lod;      // views per side
    vec2 cell = vec2(float(uint(gl_InstanceIndex) % g), float(uint(gl_InstanceIndex) / g));
    vec3 d = treeImpostorDirection((cell + 0.5) / float(g));
    vec3 right, up;
    treeImpostorBasis(d, right, up);
    vec3 q = p - vec3(0.0, 0.0, m.shape.w);
    float r = m.shape.z;
    vec2 local = vec2(dot(q, right), -dot(q, up)) / r;  // y down, as the atlas' rows
    vPos = p;
    vNormal = n;
    vThreshold = 1.0;
    vInstance = 0u;
    vColour = vec4(m.leaf.rgb, 1.0);
    vCell = local;
    // Reverse-Z: nearest the viewer 1.
    gl_Position = vec4((cell + 0.5 + 0.5 * local) / float(g) * 2.0 - 1.0, 0.5 + 0.5 * dot(q, d) / r, 1.0);
    return;
  }
  uvec4 entry = treeVisible[gl_InstanceIndex];
  TreeInstanceGpu t = treeInstances[entry.x];
  uint seed = t.seed;
  float threshold = uintBitsToFloat(entry.y);
  // A crown's core (kind 2, drawn opaque by tree_core.frag) cannot dither out: while its level
  // fades out (threshold 1 … 2) it shrinks towards the crown's centre instead, hidden by the
  // cards around it and the level fading in (whose own core, or the impostor, stands in for it).
  // Nor within the near fade (treeNearKeep): it shrinks away as the camera comes within half the
  // fade of the crown's reach (its radius around the crown's centre), before the camera is inside it.
  if (inKind == 2u) {
    vec3 centre = vec3(0.0, 0.0, m.shape.w);
    float keep = threshold > 1.0 ? clamp(2.0 - threshold, 0.0, 1.0) : 1.0;
    if (trees.limits.z > 0.0) {  // the distance from the camera to the crown's reach
      vec2 s = treeScale(t, m);
      vec3 toCentre = (t.position - trees.camera.xyz) + vec3(0.0, 0.0, m.shape.w * s.y);
      keep = min(keep, treeNearShare(length(toCentre) - m.shape.y * s.x));
    }
    if (keep < 1.0) p = centre + (p - centre) * keep;  // not at 1: the same vertices as without, bit for bit
  }

  // The chain from the vertex's branch up to the trunk, with the x on each.
  uint chain[kTreeMaxChain];
  float xs[kTreeMaxChain];
  int depth = 0;
  uint b = inBranch;
  float x = inAlong;
  for (int k = 0; k < kTreeMaxChain; ++k) {
    chain[k] = b;
    xs[k] = x;
    depth = k + 1;
    int parent = floatBitsToInt(treeBranches[firstBranch + b].link.x);
    if (parent < 0) break;
    x = treeBranches[firstBranch + b].link.y;
    b = uint(parent);
  }
  // This tree's branch angles: each branch on the trunk turned about the trunk at its attachment
  // (by up to ±20°), its twigs with it. Turning the trunk's branches about the trunk keeps the
  // crown's envelope — the one the impostors were captured with — while no two trees of a variant
  // have their branches in the same places; turning the twigs about their branches as well grew
  // the broadleaf's silhouette by 10 % (tests/render/tree_render_test.cpp).
  for (int k = 0; k < depth; ++k) {
    TreeBranchGpu br = treeBranches[firstBranch + chain[k]];
    int parent = floatBitsToInt(br.link.x);
    if (parent < 0 || floatBitsToUint(br.link.z) != 1u) continue;
    vec3 axis = treeBranches[firstBranch + uint(parent)].tC2.xyz;
    float angle = (hash01(seed ^ (chain[k] * 0x9e3779b9u)) - 0.5) * 0.7;
    p = br.originLength.xyz + rotateAbout(p - br.originLength.xyz, axis, angle);
    n = rotateAbout(n, axis, angle);
  }
  // Bending in the wind, in the model's frame (the wind turned by the tree's yaw).
  vec3 wind = treeUnrotateYaw(vec3(uintBitsToFloat(entry.z), uintBitsToFloat(entry.w), 0.0), seed);
  float time = treeTime();
  vec3 offset = vec3(0.0);
  if (dot(wind, wind) > 1e-6) {
    for (int k = 0; k < depth; ++k) {
      TreeBranchGpu br = treeBranches[firstBranch + chain[k]];
      float phase = hash01(seed + chain[k] * 0x632be5abu) * 6.2831853;
      vec2 amp = branchAmplitude(wind, br.rC4.xyz, br.sFrequency.xyz, br.link.w, br.sFrequency.w, phase, time);
      offset += branchOffset(br.tC2.xyz, br.rC4.xyz, br.sFrequency.xyz, br.originLength.w, br.tC2.w, br.rC4.w, xs[k], amp);
    }
    if (inKind == 1u) {
      vec3 tangent = normalize(cross(n, abs(n.z) < 0.9 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0)));
      float f = treeBranches[firstBranch + inBranch].sFrequency.w * 4.0;
      offset += leafFlutter(n, tangent, inFlutter, f, hash01(seed ^ uint(gl_VertexIndex)) * 6.2831853, length(wind), time);
    }
  }
  p += offset;

  vec2 scale = treeScale(t, m);
  // The trunk keeps its girth for its height: a crown stretched wide (treeScale) does not fatten it.
  float sxy = (inKind == 0u && inBranch == 0u) ? min(scale.x, kTrunkStretch * scale.y) : scale.x, sz = scale.y;
  mat3 rotation = treeRotation(seed);
  vec3 world = rotation * vec3(p.xy * sxy, p.z * sz);
  vec3 rel = (t.position - trees.camera.xyz) + world;
  vNormal = rotation * normalize(vec3(n.xy / sxy, n.z / sz));
  vPos = rel;
  vThreshold = threshold;
  vInstance = entry.x;
  vec4 ground = treeInstanceColour(t.colour);
  vColour = vec4(treeLeafAlbedo(m.leaf.rgb, ground.rgb), ground.a);
  vSky = treeVertexAtmosphere(rel);
  vSun = sunShadow(rel, vNormal);
  gl_Position = frame.viewProj * vec4(rel, 1.0);
}
