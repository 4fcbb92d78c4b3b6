// The compute blade path's buffers (render/blade_pass.h, mirrored by render/blade_pass.cpp):
// set 2 of blades.comp, blade_args.comp and blade.vert. Every blade vertex the expansion writes,
// one record per plant (what is constant along the plant: its flat fragment inputs), the index
// list (triangles, 6 indices per quad), and the state: the indexed indirect draw, the reservation
// counters, the capacities and one dispatch per species.

struct BladeVertex {
  vec3 pos;     // camera-relative
  uint plant;   // bits 0–28: the plant record; 29–30: kind (0 blade, 1 stone, 2 flower head); 31: shadow
  uvec2 colour; // packHalf2x16(r, g), packHalf2x16(b, 0): lit (common/plant_lighting.glsl); shadows 0
  uint blade;   // packSnorm2x16(x: −1 … 1 across, y: 0 root … 1 tip)
  uint species; // the catalog index (the AOV frames' species: aov.glsl)
};


const uint kBladePlantMask = 0x1fffffffu;
const uint kBladeKindShift = 29u;
const uint kBladeShadowBit = 0x80000000u;

// The vertex stage only reads (vertex-stage stores need a device feature): it defines
// BLADE_ACCESS as readonly before including this file.
#ifndef BLADE_ACCESS
#define BLADE_ACCESS
#endif
layout(set = 2, binding = 0, std430) BLADE_ACCESS buffer BladeVertices { BladeVertex bladeVertices[]; };
layout(set = 2, binding = 2, std430) BLADE_ACCESS buffer BladeIndices { uint bladeIndices[]; };
layout(set = 2, binding = 3, std430) BLADE_ACCESS buffer BladeState {
  uint drawIndexCount, drawInstanceCount, drawFirstIndex;  // VkDrawIndexedIndirectCommand
  int drawVertexOffset;
  uint drawFirstInstance;
  uint reservedVertices, reservedIndices, reservedPlants;  // atomics: what the plants asked for
  uint vertexCapacity, indexCapacity, plantCapacity;        // what the buffers hold
  uint droppedPlants;                                        // plants that did not fit (not drawn)
  uvec4 dispatches[kMaxSpecies];                             // VkDispatchIndirectCommand per species (w unused)
} state;
