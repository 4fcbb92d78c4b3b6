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

// PlantPush::flags: one table for every shader that reads the word (plant_common.glsl's kFlag*,
// blade_args.comp's kFlagArgsFinish). Bits 8 … 15 hold the MSAA sample count. Two flags once
// shared bit 16, so --plant-fades off made the compute blade path's argument pass finish early
// and the frame never ended.
inline constexpr uint32_t kPlantFlagShadows = 1, kPlantFlagFlatColour = 2, kPlantFlagFullDetail = 4,
                          kPlantSamplesShift = 8, kPlantFlagHardFades = 1u << 16,
                          kPlantFlagArgsFinish = 1u << 17;  // the compute blade path's second args pass
static_assert((kPlantFlagHardFades & kPlantFlagArgsFinish) == 0 && (kPlantFlagArgsFinish >> kPlantSamplesShift) > 0xff);

}  // namespace vegstream::render
