#pragma once
// The simulation's shared GLSL (simulation/shared/*.glsl) compiled as C++: the CPU reference of the
// wind field, the virtual blades and the drawn blades' response, the same source text the GPU
// runs. Everything is in vegstream::simulation::shader, with GLSL's vector types (glm).

#include "simulation/shared/glsl_compat.h"

namespace vegstream::simulation::shader {
#include "simulation/shared/simulation_layout.glsl"
#include "simulation/shared/grid_index.glsl"
#include "simulation/shared/wind_field.glsl"
#include "simulation/shared/virtual_blade.glsl"
#include "simulation/shared/blade_response.glsl"
#include "simulation/shared/tree_bending.glsl"
}  // namespace vegstream::simulation::shader

#undef VS_INLINE
#undef VS_INOUT
#undef VS_SIM_ARG
#undef VS_SIM
