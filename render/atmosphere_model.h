#pragma once
// The atmosphere's shared GLSL (shaders/common/atmosphere_model.glsl and atmosphere_march.glsl)
// compiled as C++: the CPU reference of the LUT passes (render/atmosphere_pass.h), the same source
// text the GPU runs. Where the GPU reads its transmittance and multiple-scattering LUTs, the
// reference integrates them by brute force (marches of many steps), so comparing the two measures
// the LUTs' own error. Everything is in vegstream::render::atmosphere, with GLSL's vector types.

#include <cmath>

#include "simulation/shared/glsl_compat.h"

// glsl_compat.h defines these once; simulation/shared_code.h undefines them after its use.
#ifndef VS_INLINE
#define VS_INLINE inline
#define VS_INOUT(T) T&
#define VEGSTREAM_ATMOSPHERE_DEFINED_VS
#endif

namespace vegstream::render::atmosphere {
using namespace vegstream::simulation::shader;
using glm::exp;
using std::acos;
using std::exp;

#include "shaders/common/atmosphere_model.glsl"

// The lookups atmosphere_march.glsl reads, by brute force.
inline vec3 sunTransmittance(float r, float muS) {
  return rayHitsGround(r, muS) ? vec3(0.0f) : transmittanceToTopMarched(r, muS, 256);
}
inline vec3 multiScattering(float r, float muS);

#include "shaders/common/atmosphere_march.glsl"

inline vec3 multiScattering(float r, float muS) { return multiScatteringTransfer(r, muS, 10, 20); }

}  // namespace vegstream::render::atmosphere

#ifdef VEGSTREAM_ATMOSPHERE_DEFINED_VS
#undef VS_INLINE
#undef VS_INOUT
#undef VEGSTREAM_ATMOSPHERE_DEFINED_VS
#endif
