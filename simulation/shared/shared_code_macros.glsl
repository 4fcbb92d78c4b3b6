// The macros of the GLSL that C++ compiles too (simulation/shared/glsl_compat.h,
// render/atmosphere_model.h), as GLSL reads them: one definition for every shared file
// (simulation_layout.glsl here, the atmosphere's shaders/common/atmosphere.glsl and
// atmosphere_lut_io.glsl). C++ defines them first (glsl_compat.h), so this block is skipped there.
#ifndef VS_INLINE
#define VS_INLINE
#define VS_INOUT(T) inout T
#define VS_SIM_ARG
#define VS_SIM
#endif
