#ifndef SIMULATION_BLOCK_GLSL
#define SIMULATION_BLOCK_GLSL
// The shared simulation's per-frame block (set 0, binding 1: render/simulation_pass.h) and its
// shared code (simulation/shared/*.glsl, also compiled as the C++ reference by
// simulation/shared_code.h): the wind field, the virtual blades, the drawn blades' response.
#include "simulation/shared/simulation_layout.glsl"
layout(set = 0, binding = 1, std140) uniform SimulationBlock { SimulationParams sim; };
#include "simulation/shared/grid_index.glsl"
#include "simulation/shared/wind_field.glsl"
#include "simulation/shared/virtual_blade.glsl"
#include "simulation/shared/blade_response.glsl"
#endif
