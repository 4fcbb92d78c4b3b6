#version 450
#extension GL_GOOGLE_include_directive : require
// After the classify dispatches: one indirect draw per species (instances = its groups, clamped
// to the buffer) and a copy of the counters for the frame's figures.
layout(local_size_x = 16) in;
#include "classify_layout.glsl"

struct DrawIndirect { uint vertexCount, instanceCount, firstVertex, firstInstance; };
layout(set = 0, binding = 0, std430) readonly buffer Counters {
  uint groups[kMaxSpecies];
  uint plants[kMaxSpecies];
  uint culledGroups, culledPlants;
  uint wanted[kMaxSpecies];
};
layout(set = 0, binding = 1, std430) writeonly buffer Draws { DrawIndirect draws[kMaxSpecies]; };
layout(set = 0, binding = 2, std430) writeonly buffer Figures {
  uint figureGroups[kMaxSpecies];
  uint figurePlants[kMaxSpecies];
  uint figureCulledGroups, figureCulledPlants;
  uint figureWanted[kMaxSpecies];
};
// patchMask bit s: species s is drawn by a plant pipeline (one patch vertex per group).
layout(push_constant) uniform Push { uint verticesPerGroup; uint speciesCapacity; uint patchMask; } pc;

void main() {
  uint s = gl_LocalInvocationID.x;
  uint vertices = ((pc.patchMask >> s) & 1u) != 0u ? 1u : pc.verticesPerGroup;
  draws[s] = DrawIndirect(vertices, min(groups[s], pc.speciesCapacity), 0u, 0u);
  figureGroups[s] = groups[s];
  figurePlants[s] = plants[s];
  figureWanted[s] = wanted[s];
  if (s == 0u) {
    figureCulledGroups = culledGroups;
    figureCulledPlants = culledPlants;
  }
}
