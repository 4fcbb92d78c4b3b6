#pragma once
// The push constants every plant pipeline shares — the tessellation path (plant_pass.h) and the
// compute blade path (blade_pass.h): mirrors PlantPush in shaders/common/plant_common.glsl.

#include <cstdint>

namespace vegstream::render {

struct PlantPush {
  uint32_t species, speciesCapacity, maxSegments, flags;
  float lodDistanceM, tableLogKMin, tableLogKStep;
  uint32_t tableRows;
  float shadowDistanceM;
};
static_assert(sizeof(PlantPush) == 36);

// PlantPush::flags.
inline constexpr uint32_t kPlantFlagShadows = 1, kPlantFlagFlatColour = 2, kPlantFlagFullDetail = 4,
                          kPlantSamplesShift = 8, kPlantFlagHardFades = 1u << 16;

}  // namespace vegstream::render
