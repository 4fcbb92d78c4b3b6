#pragma once
// C++ mirror of the TerrainDetail uniform block of shaders/common/terrain_detail.glsl (std140):
// the terrain-type table of vegetation/terrain_types.h (colour-score parameters, core seed
// ../shared/seeds/001_3eca9f2c7752e4fb.txt §3.3 eq. 16) plus how the detail textures tile and
// fade. Only vec4 members and vec4 arrays (stride 16), so the std140 layout equals the C++
// layout; the static_asserts keep the two in step. No Vulkan here: packing is testable alone.

#include <cstddef>
#include <span>

#include <glm/vec4.hpp>

#include "vegetation/terrain_types.h"

namespace vegstream::render {

// World-space tiling: the camera position enters the shader modulo kDetailPeriodM (computed in
// double, frame uniforms `detail`), so coordinates stay small and the pattern stays put on the
// ground as the camera moves. Both repeat counts are whole numbers per period, so the pattern is
// continuous when the modulo wraps.
inline constexpr double kDetailPeriodM = 256.0;
inline constexpr float kDetailFineRepeats = 32.0f;   // 8 m per repeat of the texture (3 cm texels)
inline constexpr float kDetailCoarseRepeats = 7.0f;  // 36.6 m: breaks up the fine repeat

struct DetailSettings {
  float fadeStartM = 150.0f;  // full detail closer than this (distance from the camera)
  float fadeEndM = 1500.0f;   // none beyond this: far terrain is exactly the imagery
  float strength = 1.0f;      // 0 … 1: how much of the modulation is applied
  float coarseShare = 0.35f;  // share of the coarse scale in the modulation
};

struct TerrainDetailUniforms {
  glm::vec4 params;  // x: type count, y: fade start (m), z: fade end (m), w: strength
  glm::vec4 tiling;  // x: period (m), y: fine repeats per period, z: coarse repeats, w: coarse share
  glm::vec4 reference[vegetation::kMaxTerrainTypes];  // xyz: reference HSV, w: exponent p
  glm::vec4 weights[vegetation::kMaxTerrainTypes];    // xyz: channel weights, w: detail layer (surface)
  glm::vec4 ndvi[vegetation::kMaxTerrainTypes];       // x: NDVI reference, y: NDVI weight
};

static_assert(offsetof(TerrainDetailUniforms, params) == 0);
static_assert(offsetof(TerrainDetailUniforms, tiling) == 16);
static_assert(offsetof(TerrainDetailUniforms, reference) == 32);
static_assert(offsetof(TerrainDetailUniforms, weights) == 32 + 16 * vegetation::kMaxTerrainTypes);
static_assert(offsetof(TerrainDetailUniforms, ndvi) == 32 + 32 * vegetation::kMaxTerrainTypes);
static_assert(sizeof(TerrainDetailUniforms) == 32 + 48 * vegetation::kMaxTerrainTypes);
static_assert(vegetation::kMaxTerrainTypes == 16, "shaders/common/terrain_detail.glsl declares 16");

// The block for `types` (at most kMaxTerrainTypes; more are cut off) and `settings`.
TerrainDetailUniforms packTerrainDetail(std::span<const vegetation::TerrainType> types,
                                        const DetailSettings& settings = {});

}  // namespace vegstream::render
