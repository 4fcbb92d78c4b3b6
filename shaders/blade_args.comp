#version 450
#extension GL_GOOGLE_include_directive : require
// The compute blade path's bookkeeping (render/blade_pass.h), one workgroup:
//  without kFlagArgsFinish, before blades.comp: one dispatch per species drawn by blades (pc.species = the
//    species mask) of ⌈groups / 64⌉ workgroups, from the classify pass's indirect draws;
//  with it, after blades.comp: the indexed indirect draw (the reserved indices, clamped to the buffer)
//    and a copy of the counters for the frame's figures.
layout(local_size_x = 16) in;
#include "frame_uniforms.glsl"
#include "philox.glsl"
#include "seeding.glsl"
#include "classify_layout.glsl"
#include "plant_common.glsl"
#include "blade_layout.glsl"

const uint kFlagArgsFinish = 0x20000u;  // render/plant_push.h kPlantFlagArgsFinish

layout(set = 2, binding = 4, std430) readonly buffer ClassifyDraws { uvec4 classifyDraws[kMaxSpecies]; };
layout(set = 2, binding = 5, std430) writeonly buffer Figures {
  uint figReservedVertices, figReservedIndices, figReservedPlants, figDropped, figDrawnIndices;
};

void main() {
  uint s = gl_LocalInvocationID.x;
  if ((pc.flags & kFlagArgsFinish) == 0u) {
    bool drawn = ((pc.species >> s) & 1u) != 0u;
    state.dispatches[s] = uvec4(drawn ? (classifyDraws[s].y + 63u) / 64u : 0u, 1u, 1u, 0u);
    return;
  }
  if (s != 0u) return;
  uint drawn = min(state.reservedIndices, state.indexCapacity);
  state.drawIndexCount = drawn;
  figReservedVertices = state.reservedVertices;
  figReservedIndices = state.reservedIndices;
  figReservedPlants = state.reservedPlants;
  figDropped = state.droppedPlants;
  figDrawnIndices = drawn;
}
