#version 460
#extension GL_GOOGLE_include_directive : require
// The trees' near lists front to back (issue 41 item 7): one workgroup per model and mesh level
// (full, reduced), after the classify (tree_classify.comp) has appended them in whatever order its
// atomics gave. A bitonic sort (Batcher 1968) in shared memory of the region's first kTreeSortMax
// entries by (distance to the camera, instance), so each model's trees — and their cores, drawn
// from the same lists — go nearest first: the depth a near crown writes lets the hardware reject
// the cards behind it before they are shaded, where a far tree drawn first is shaded and then
// overdrawn. The order changes no pixel: the draws are opaque and depth-tested. A region longer
// than kTreeSortMax (none of the bundled flights comes near it) keeps its tail as appended.
layout(local_size_x = 256) in;
#include "common/frame_uniforms.glsl"
#include "common/tree_layout.glsl"

layout(set = 1, binding = 5, std430) readonly buffer MeshDraws { uint meshDraws[]; };  // per model × 2: VkDrawIndexedIndirectCommand

const uint kTreeSortMax = 512u;
shared uvec4 entries[kTreeSortMax];
shared float distances[kTreeSortMax];
shared uint order[kTreeSortMax];

bool before(uint a, uint b) {
  float da = distances[a], db = distances[b];
  return da < db || (da == db && entries[a].x < entries[b].x);
}

void main() {
  uint model = gl_WorkGroupID.x / 2u, lod = gl_WorkGroupID.x % 2u;
  if (model >= trees.counts.y) return;
  uint count = min(min(meshDraws[(model * 2u + lod) * 5u + 1u], treeRegionCapacity(lod)), kTreeSortMax);
  if (count < 2u) return;
  uint base = treeRegionBase(model, lod);
  uint n = 2u;
  while (n < count) n *= 2u;
  for (uint i = gl_LocalInvocationID.x; i < n; i += gl_WorkGroupSize.x) {
    order[i] = i;
    if (i < count) {
      entries[i] = treeVisible[base + i];
      distances[i] = length(treeInstances[entries[i].x].position - trees.camera.xyz);
    } else {  // padding: after every entry
      entries[i] = uvec4(0xffffffffu);
      distances[i] = uintBitsToFloat(0x7f800000u);  // +inf
    }
  }
  barrier();
  for (uint k = 2u; k <= n; k *= 2u)
    for (uint j = k / 2u; j > 0u; j /= 2u) {
      for (uint i = gl_LocalInvocationID.x; i < n; i += gl_WorkGroupSize.x) {
        uint l = i ^ j;
        if (l <= i) continue;
        uint a = order[i], b = order[l];
        bool ascending = (i & k) == 0u;
        if (before(b, a) == ascending) {
          order[i] = b;
          order[l] = a;
        }
      }
      barrier();
    }
  for (uint i = gl_LocalInvocationID.x; i < count; i += gl_WorkGroupSize.x) treeVisible[base + i] = entries[order[i]];
}
