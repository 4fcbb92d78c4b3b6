#pragma once
// Classification markers: until the species pipelines arrive (issue 8), one upright triangle per
// classified plant in its species' colour, drawn with the classify pass's indirect draws (one per
// species) so the classification can be seen (shaders/plant_marker.vert).

#include "render/classify_pass.h"

namespace vegstream::render {

class PlantMarkerPass {
 public:
  PlantMarkerPass(const Context& ctx, VkDescriptorSetLayout frameLayout, VkSampleCountFlagBits samples);

  // Inside rendering, after the terrain: draws slot `slot`'s classification, except the species
  // in `skipMask` (bit s: drawn by a plant pipeline instead).
  void record(VkCommandBuffer cmd, int slot, VkDescriptorSet frameSet, const ClassifyPass& classify,
              uint32_t skipMask = 0);

  // Vertices one indirect draw instance covers (3 per plant of a full cluster).
  static uint32_t verticesPerGroup(uint32_t clusterSize) { return 3 * clusterSize; }

 private:
  const Context* ctx_;
  DescriptorSetLayout setLayout_;
  DescriptorPool pool_;
  std::array<VkDescriptorSet, ClassifyPass::kSlots> sets_{};
  PipelineLayout layout_;
  Pipeline pipeline_;
};

}  // namespace vegstream::render
