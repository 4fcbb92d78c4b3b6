// Overflow thinning (overflow_thinning.h): view-independent priorities, a pressure from the
// groups wanted, and the size factor between them.
#include "vegetation/overflow_thinning.h"

#include <algorithm>
#include <cassert>

#include "vegetation/philox.h"
#include "vegetation/plant_seeding.h"

namespace vegstream::vegetation {

float groupPriority(uint64_t key, uint32_t cluster, uint32_t seed) {
  const uint32_t y =
      philox((cluster << 8) | philox_slot::kSpecies, static_cast<uint32_t>(key >> 32), static_cast<uint32_t>(key)).y;
  return u01(y + seed * 0x9E3779B9u);
}

float thinningFade(float pressure, float priority) {
  const float edge = (1.0f + kThinningBand) * (1.0f - pressure);
  return std::clamp((edge - priority) / kThinningBand, 0.0f, 1.0f);
}

float thinningPressure(uint64_t wantedGroups, uint32_t capacity) {
  assert(capacity > 0);
  const double target = kThinningStart * static_cast<double>(capacity);
  if (static_cast<double>(wantedGroups) <= target) return 0.0f;
  return static_cast<float>(1.0 - target / static_cast<double>(wantedGroups));
}

}  // namespace vegstream::vegetation
