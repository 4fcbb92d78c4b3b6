#pragma once
// The species pipelines (core seed ../shared/seeds/001_3eca9f2c7752e4fb.txt §2.3–2.4, §3.5,
// §3.6): one Vulkan pipeline per renderer kind — grass, gravel, flowers — fed by the classify
// pass's per-species buffers and indirect draws. Each group is one patch; the tessellation
// control stage turns it into as many isolines as the group has plants, each of
// n = n_max / max(‖v‖, 1)² segments (eq. 4); the evaluation stage places each plant on its
// solved blade shape (vegetation/blade_shape.h, a texture sampled by stiffness and position
// along the blade); the kind's geometry stage extrudes it (tapered blade strips, gravel
// diamonds, stems with flower heads) and, as a second invocation, its planar shadow on the seed
// triangle's plane along the sunlight; the fragment stage shades with eq. 13–14 from the imagery
// colour under the plant and turns the blade's alpha mask into its MSAA sample mask
// (alpha-to-coverage computed in the shader: the same on every device; an alpha test without
// MSAA). Kinds without a pipeline (trees, for now) stay markers (plant_marker_pass.h).
//
// A new kind is catalog data plus one geometry shader: the vertex, control, evaluation and
// fragment stages are shared (shaders/plant.*, shaders/common/plant_common.glsl).

#include <array>

#include "render/classify_pass.h"
#include "render/context.h"
#include "render/frame_types.h"
#include "render/gpu_resources.h"
#include "render/handle.h"
#include "render/plant_push.h"
#include "vegetation/blade_shape.h"

namespace vegstream::render {

class PlantPass {
 public:
  // `stiffnessUnit`: the table's k′ for a species stiffness of 1 (the catalog's stiffness is
  // relative to the critical stiffness of the table's blade).
  PlantPass(const Context& ctx, VkDescriptorSetLayout frameLayout, VkSampleCountFlagBits samples,
            const vegetation::BladeShapeTable& table, double stiffnessUnit);

  // Bit s set: species s of `classify`'s catalog has a plant pipeline here.
  static uint32_t patchMask(const ClassifyPass& classify);

  // Inside rendering: draws slot `slot`'s classified plants. `imagery` is the imagery array's
  // sRGB view (the ground colour under each plant).
  void record(VkCommandBuffer cmd, int slot, VkDescriptorSet frameSet, const ClassifyPass& classify,
              VkImageView imagery, const PlantDrawOptions& options);

  uint64_t gpuBytes() const { return table_.bytes; }

  // What the compute blade path (blade_pass.h) shares with these pipelines: the push constants
  // of species `species`, the blade-shape table and the samplers.
  PlantPush pushFor(uint32_t species, const ClassifyPass& classify, const PlantDrawOptions& options) const;
  VkImageView tableView() const { return table_.view.get(); }
  VkSampler tableSampler() const { return tableSampler_.get(); }
  VkSampler imagerySampler() const { return imagerySampler_.get(); }

 private:
  const Context* ctx_;
  uint32_t samples_ = 1;  // MSAA samples: the fragment stage turns alpha into that many bits
  GpuImage table_;
  int tableRows_ = 0;
  float tableLogKMin_ = 0.0f, tableLogKStep_ = 1.0f;
  Sampler tableSampler_, imagerySampler_;
  DescriptorSetLayout setLayout_;
  DescriptorPool pool_;
  std::array<VkDescriptorSet, ClassifyPass::kSlots> sets_{};
  PipelineLayout layout_;
  std::array<Pipeline, 3> pipelines_;  // by vegetation::RendererKind: grass, gravel, flowers
  Pipeline speedOfLight_;              // PlantDrawOptions::speedOfLight
};

}  // namespace vegstream::render
