// The macros of the GLSL that C++ compiles too (simulation/shared/glsl_compat.h,
// render/atmosphere_model.h), as GLSL reads them; simulation/shared/simulation_layout.glsl
// defines the same set.
#ifndef VS_INLINE
#define VS_INLINE
#define VS_INOUT(T) inout T
#define VS_SIM_ARG
#define VS_SIM
#endif
