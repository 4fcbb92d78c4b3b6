// The species pipelines (plant_pass.h), core seed 001_3eca9f2c7752e4fb.txt §2.3–2.4, §3.5–3.6.
#include "render/plant_pass.h"

#include <cmath>
#include <cstring>
#include <string>

#include "render/descriptors.h"
#include "render/pipeline_builder.h"
#include "render/plant_push.h"
#include "render/render_targets.h"
#include "render/vk_check.h"
#include "shaders/flowers.geom.h"
#include "shaders/grass.geom.h"
#include "shaders/gravel.geom.h"
#include "shaders/plant.frag.h"
#include "shaders/plant.tesc.h"
#include "shaders/plant.tese.h"
#include "shaders/plant.vert.h"
#include "shaders/sol.frag.h"
#include "shaders/sol.geom.h"
#include "shaders/sol.tese.h"

namespace vegstream::render {
namespace {

constexpr VkShaderStageFlags kStages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_TESSELLATION_CONTROL_BIT |
                                       VK_SHADER_STAGE_TESSELLATION_EVALUATION_BIT | VK_SHADER_STAGE_GEOMETRY_BIT |
                                       VK_SHADER_STAGE_FRAGMENT_BIT;

bool hasPipeline(uint32_t kind) {
  using K = vegetation::RendererKind;
  return kind == static_cast<uint32_t>(K::Grass) || kind == static_cast<uint32_t>(K::Gravel) ||
         kind == static_cast<uint32_t>(K::Flowers);
}

Sampler nearestClampSampler(const Context& ctx, const std::string& name) {
  VkSamplerCreateInfo sci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  sci.magFilter = sci.minFilter = VK_FILTER_NEAREST;
  sci.addressModeU = sci.addressModeV = sci.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  VkSampler s;
  vkCheck(vkCreateSampler(ctx.device(), &sci, nullptr, &s), "vkCreateSampler");
  ctx.setName(VK_OBJECT_TYPE_SAMPLER, s, name);
  return Sampler(ctx.device(), s);
}

// A plant pipeline: tessellation of one patch per cluster, then `geom`'s triangles, shaded by
// `frag`, two-sided.
Pipeline plantPipeline(const Context& ctx, VkPipelineLayout layout, VkSampleCountFlagBits samples, const char* name,
                       std::span<const uint32_t> tese, std::span<const uint32_t> geom, std::span<const uint32_t> frag) {
  GraphicsPipelineDesc desc;
  desc.name = name;
  desc.stages = {{VK_SHADER_STAGE_VERTEX_BIT, spv_plant_vert},
                 {VK_SHADER_STAGE_TESSELLATION_CONTROL_BIT, spv_plant_tesc},
                 {VK_SHADER_STAGE_TESSELLATION_EVALUATION_BIT, tese},
                 {VK_SHADER_STAGE_GEOMETRY_BIT, geom},
                 {VK_SHADER_STAGE_FRAGMENT_BIT, frag}};
  desc.topology = VK_PRIMITIVE_TOPOLOGY_PATCH_LIST;
  desc.patchControlPoints = 1;
  desc.cullMode = VK_CULL_MODE_NONE;  // blades are two-sided
  desc.samples = samples;
  desc.colorFormat = kColorFormat;
  desc.depthFormat = kDepthFormat;
  desc.layout = layout;
  return createGraphicsPipeline(ctx, desc);
}

}  // namespace

PlantPass::PlantPass(const Context& ctx, VkDescriptorSetLayout frameLayout, VkSampleCountFlagBits samples,
                     const vegetation::BladeShapeTable& table, double stiffnessUnit)
    : ctx_(&ctx), samples_(static_cast<uint32_t>(samples)) {
  // The blade-shape table: segments × rows texels of (lateral, height, inclination, 0).
  const auto width = static_cast<uint32_t>(table.segments), height = static_cast<uint32_t>(table.rows);
  table_ = createImage2D(ctx, {width, height}, VK_FORMAT_R32G32B32A32_SFLOAT,
                         VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, VK_SAMPLE_COUNT_1_BIT,
                         "blade shape table");
  const VkDeviceSize bytes = table.texels.size() * sizeof(float);
  GpuBuffer staging =
      createBuffer(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::HostUpload, "blade shape table staging");
  std::memcpy(staging.mapped, table.texels.data(), bytes);
  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    recordImageArrayUpload(cmd, staging, table_, VK_PIPELINE_STAGE_2_PRE_RASTERIZATION_SHADERS_BIT);
  });
  tableRows_ = table.rows;
  tableLogKMin_ = static_cast<float>(std::log(table.kMin / stiffnessUnit));
  tableLogKStep_ = static_cast<float>(std::log(table.kMax / table.kMin) / (table.rows - 1));
  tableSampler_ = nearestClampSampler(ctx, "blade shape sampler");
  imagerySampler_ = createLinearClampSampler(ctx, "plant imagery sampler");

  const VkDescriptorSetLayoutBinding bindings[] = {{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, kStages, nullptr},
                                                   {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, kStages, nullptr},
                                                   {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, kStages, nullptr},
                                                   {3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, kStages, nullptr},
                                                   {4, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, kStages, nullptr}};
  setLayout_ = createLayout(ctx, bindings, "plant set layout");
  constexpr auto slots = static_cast<uint32_t>(ClassifyPass::kSlots);
  const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, slots},
                                        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 2 * slots},
                                        {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 2 * slots}};
  pool_ = createPool(ctx, sizes, slots, "plant pool");
  allocateSlotSets(ctx, pool_.get(), setLayout_.get(), sets_, "plant set");
  const VkPushConstantRange push{kStages, 0, sizeof(PlantPush)};
  const VkDescriptorSetLayout sets[] = {frameLayout, setLayout_.get()};
  layout_ = createPipelineLayout(ctx, sets, {&push, 1}, "plant pipeline layout");

  const auto makePipeline = [&](const char* name, std::span<const uint32_t> tese, std::span<const uint32_t> geom,
                                std::span<const uint32_t> frag) {
    return plantPipeline(ctx, layout_.get(), samples, name, tese, geom, frag);
  };
  pipelines_[0] = makePipeline("grass pipeline", spv_plant_tese, spv_grass_geom, spv_plant_frag);
  pipelines_[1] = makePipeline("gravel pipeline", spv_plant_tese, spv_gravel_geom, spv_plant_frag);
  pipelines_[2] = makePipeline("flowers pipeline", spv_plant_tese, spv_flowers_geom, spv_plant_frag);
  speedOfLight_ = makePipeline("speed-of-light plant pipeline", spv_sol_tese, spv_sol_geom, spv_sol_frag);
}

uint32_t PlantPass::patchMask(const ClassifyPass& classify) {
  uint32_t mask = 0;
  for (uint32_t s = 0; s < classify.speciesCount(); ++s)
    if (hasPipeline(classify.kind(s))) mask |= 1u << s;
  return mask;
}

PlantPush PlantPass::pushFor(uint32_t species, const ClassifyPass& classify, const PlantDrawOptions& options) const {
  uint32_t flags = 0;
  if (options.shadows) flags |= kPlantFlagShadows;
  flags |= samples_ << kPlantSamplesShift;  // the fragment stage's computed alpha-to-coverage
  if (options.fullDetail) flags |= kPlantFlagFullDetail;
  if (options.flatColour) flags |= kPlantFlagFlatColour;
  if (!options.fades) flags |= kPlantFlagHardFades;
  return PlantPush{species,
                   classify.clustersPerSpecies(),
                   options.maxSegments,
                   flags,
                   options.lodDistanceM,
                   tableLogKMin_,
                   tableLogKStep_,
                   static_cast<uint32_t>(tableRows_),
                   options.shadowDistanceM};
}

void PlantPass::record(VkCommandBuffer cmd, int slot, VkDescriptorSet frameSet, const ClassifyPass& classify,
                       VkImageView imagery, const PlantDrawOptions& options) {
  const uint32_t mask = patchMask(classify);
  if (mask == 0 || classify.triangles(slot) == VK_NULL_HANDLE) return;
  // The slot's previous frame has finished: its set may be rewritten (buffers may have grown).
  const VkDescriptorSet set = sets_[size_t(slot)];
  writeUniformBuffer(*ctx_, set, classify.species(), sizeof(SpeciesBlock), 0);
  writeStorageBuffer(*ctx_, set, classify.triangles(slot), 1);
  writeStorageBuffer(*ctx_, set, classify.records(slot), 2);
  writeSampledImage(*ctx_, set, tableSampler_.get(), table_.view.get(), 3);
  writeSampledImage(*ctx_, set, imagerySampler_.get(), imagery, 4);
  const VkDescriptorSet sets[] = {frameSet, set};
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_.get(), 0, 2, sets, 0, nullptr);
  for (uint32_t s = 0; s < classify.speciesCount(); ++s) {
    if (!((mask >> s) & 1u)) continue;
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS,
                      options.speedOfLight ? speedOfLight_.get() : pipelines_[classify.kind(s)].get());
    const PlantPush push = pushFor(s, classify, options);
    vkCmdPushConstants(cmd, layout_.get(), kStages, 0, sizeof(push), &push);
    vkCmdDrawIndirect(cmd, classify.indirect(slot), VkDeviceSize{s} * sizeof(VkDrawIndirectCommand), 1,
                      sizeof(VkDrawIndirectCommand));
  }
}

}  // namespace vegstream::render
