#pragma once
// Lets C++ compile the simulation's shared GLSL (simulation/shared/*.glsl) as its CPU reference:
// the GPU and the CPU run the same source text, so they cannot drift apart (issue 19: "the CPU
// reference and the GPU agree within 1e-4"). Include only through simulation/shared_code.h, which
// wraps the GLSL in a namespace.
//
// The shared files keep to a subset both languages read alike: float literals with an f suffix,
// no swizzles (v.x, v.y only), structs instead of array parameters (C++ arrays decay to pointers),
// no constructors of structs, and three macros for what differs:
//   VS_INLINE        inline in C++, nothing in GLSL
//   VS_INOUT(T)      T& in C++, inout T in GLSL
//   VS_SIM_ARG/VS_SIM  the simulation block: a parameter in C++, the uniform block `sim` in GLSL

#include <cmath>
#include <cstdint>

#include <glm/common.hpp>
#include <glm/exponential.hpp>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#define VS_INLINE inline
#define VS_INOUT(T) T&
#define VS_SIM_ARG const SimulationParams &sim,
#define VS_SIM sim,

namespace vegstream::simulation::shader {
using glm::ivec2;
using glm::ivec4;
using glm::uvec2;
using glm::vec2;
using glm::vec3;
using glm::vec4;
using uint = std::uint32_t;

using glm::abs;
using glm::clamp;
using glm::cross;
using glm::dot;
using glm::floor;
using glm::fract;
using glm::length;
using glm::max;
using glm::min;
using glm::mix;
using glm::normalize;
using glm::smoothstep;
using std::cos;
using std::pow;
using std::sin;
using std::sqrt;
// GLSL's two-argument atan is C's atan2.
inline float atan(float y, float x) { return std::atan2(y, x); }
}  // namespace vegstream::simulation::shader
