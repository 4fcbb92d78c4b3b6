#include "render/terrain_detail.h"

#include <algorithm>

namespace vegstream::render {

TerrainDetailUniforms packTerrainDetail(std::span<const vegetation::TerrainType> types,
                                        const DetailSettings& settings) {
  TerrainDetailUniforms u{};
  const size_t count = std::min(types.size(), vegetation::kMaxTerrainTypes);
  u.params = {static_cast<float>(count), settings.fadeStartM, settings.fadeEndM, settings.strength};
  u.tiling = {static_cast<float>(kDetailPeriodM), kDetailFineRepeats, kDetailCoarseRepeats, settings.coarseShare};
  for (size_t i = 0; i < count; ++i) {
    const vegetation::ColourScoreParams& s = types[i].score;
    u.reference[i] = glm::vec4(s.reference, s.p);
    u.weights[i] = glm::vec4(s.weights, static_cast<float>(types[i].surface));
    u.ndvi[i] = glm::vec4(s.ndviReference, s.ndviWeight, 0.0f, 0.0f);
  }
  return u;
}

}  // namespace vegstream::render
