// The classify pass (classify_pass.h), core seed 001_3eca9f2c7752e4fb.txt §3.2, §3.5.
#include "render/classify_pass.h"

#include <algorithm>
#include <cassert>
#include <cstring>
#include <string>
#include <vector>

#include "render/descriptors.h"
#include "render/pipeline_builder.h"
#include "render/vk_check.h"
#include "vegetation/overflow_thinning.h"
#include "shaders/classify.comp.h"
#include "shaders/classify_finish.comp.h"
#include "vegetation/plant_bins.h"
#include "vegetation/plant_seeding.h"

namespace vegstream::render {
namespace {

// The crowns the plants thin under, into the slot's canopy buffer (a disabled header when none).
void writeCanopy(void* mapped, const vegetation::CanopyTable* canopy) {
  auto* canopyBytes = static_cast<uint8_t*>(mapped);
  const bool crowns = canopy && canopy->header.enabled != 0 &&
                      canopy->entries.size() == size_t{vegetation::kCanopyCells} * vegetation::kCanopyCells;
  const vegetation::CanopyHeader header = crowns ? canopy->header : vegetation::CanopyHeader{};
  std::memcpy(canopyBytes, &header, sizeof(header));
  if (crowns)
    std::memcpy(canopyBytes + sizeof(header), canopy->entries.data(),
                canopy->entries.size() * sizeof(vegetation::CanopyEntry));
}

constexpr VkDeviceSize kCanopyBytes = sizeof(vegetation::CanopyHeader) + VkDeviceSize{vegetation::kCanopyCells} *
                                                                          vegetation::kCanopyCells *
                                                                          sizeof(vegetation::CanopyEntry);


static_assert(kSpeciesSlots == vegetation::kMaxSpecies);
constexpr uint32_t kWorkgroup = 64;  // shaders/classify.comp local_size_x
constexpr uint32_t kMaxGroupsPerDispatch = 65535;
// groups and plants per species, then the groups and plants the occlusion test dropped.
// groups[16], plants[16], culledGroups, culledPlants, wanted[16] (classify.comp's Counters).
constexpr VkDeviceSize kCounterBytes = (3 * kSpeciesSlots + 2) * sizeof(uint32_t);
constexpr VkDeviceSize kIndirectBytes = kSpeciesSlots * sizeof(VkDrawIndirectCommand);

struct ClassifyPush {
  uint32_t orderFirst, triangleCount, capacity, clusterSize, threadBase, speciesCapacity, cull, hardFades, companions;
  uint32_t pad[3];                            // std430: the vec4 array starts at 48
  std::array<float, kSpeciesSlots> thinning;  // overflow thinning pressure per species
};
struct FinishPush {
  uint32_t verticesPerGroup, speciesCapacity, patchMask;
};

VkDescriptorSetLayoutBinding storage(uint32_t binding) {
  return {binding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
}

}  // namespace

ClassifyPass::ClassifyPass(const Context& ctx, const ClassifyOptions& options) : ctx_(&ctx), options_(options) {
  assert(options.clustersPerSpecies > 0);
  species_ = createBuffer(ctx, sizeof(SpeciesBlock), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, MemoryUse::HostUpload,
                          "classify species block");
  std::memset(species_.mapped, 0, sizeof(SpeciesBlock));
  sampler_ = createLinearClampSampler(ctx, "classify imagery sampler");
  const VkDescriptorSetLayoutBinding classifyBindings[] = {
      {0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
      storage(1),
      storage(2),
      storage(3),
      storage(4),
      {5, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
      storage(6),
      {7, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
      storage(8)};
  classifyLayout_ = createLayout(ctx, classifyBindings, "classify set layout");
  const VkDescriptorSetLayoutBinding finishBindings[] = {storage(0), storage(1), storage(2)};
  finishLayout_ = createLayout(ctx, finishBindings, "classify finish set layout");
  const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, kSlots},
                                        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 9 * kSlots},
                                        {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 2 * kSlots}};
  pool_ = createPool(ctx, sizes, 2 * kSlots, "classify pool");

  const VkPushConstantRange classifyPush{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(ClassifyPush)};
  const VkDescriptorSetLayout cl[] = {classifyLayout_.get()};
  classifyPipelineLayout_ = createPipelineLayout(ctx, cl, {&classifyPush, 1}, "classify pipeline layout");
  classify_ = createComputePipeline(ctx, classifyPipelineLayout_.get(), spv_classify_comp, "classify pipeline");
  const VkPushConstantRange finishPush{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(FinishPush)};
  const VkDescriptorSetLayout fl[] = {finishLayout_.get()};
  finishPipelineLayout_ = createPipelineLayout(ctx, fl, {&finishPush, 1}, "classify finish pipeline layout");
  finish_ =
      createComputePipeline(ctx, finishPipelineLayout_.get(), spv_classify_finish_comp, "classify finish pipeline");

  for (size_t i = 0; i < size_t{kSlots}; ++i) createSlot(i);
}

void ClassifyPass::createSlot(size_t i) {
  const Context& ctx = *ctx_;
  const VkDeviceSize recordBytes = VkDeviceSize{options_.clustersPerSpecies} * kSpeciesSlots * sizeof(PlantClusterGpu);
  Slot& s = slots_[size_t(i)];
  const std::string tag = " (slot " + std::to_string(i) + ")";
  s.counters = createBuffer(ctx, kCounterBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                            MemoryUse::DeviceLocal, "classify counters" + tag);
  // Transfer source: tests and tools read the records back.
  s.records = createBuffer(ctx, recordBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                           MemoryUse::DeviceLocal, "classify records" + tag);
  s.indirect =
      createBuffer(ctx, kIndirectBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT,
                   MemoryUse::DeviceLocal, "classify indirect draws" + tag);
  s.figures = createBuffer(ctx, kCounterBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::HostReadback,
                           "classify figures" + tag);
  std::memset(s.figures.mapped, 0, kCounterBytes);
  s.canopy = createBuffer(ctx, kCanopyBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::HostUpload,
                          "classify canopy" + tag);
  std::memset(s.canopy.mapped, 0, kCanopyBytes);  // enabled 0: no crowns
  s.triangles = GrowingBuffer(ctx, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::HostUpload,
                              "classify triangles" + tag, options_.tasks);
  s.visible = GrowingBuffer(ctx, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::DeviceLocal,
                            "classify visible triangles" + tag, options_.tasks);
  s.order = GrowingBuffer(ctx, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::HostUpload, "classify bin order" + tag,
                          options_.tasks);
  s.classifySet = allocateDescriptorSet(ctx, pool_.get(), classifyLayout_.get(), "classify set" + tag);
  s.finishSet = allocateDescriptorSet(ctx, pool_.get(), finishLayout_.get(), "classify finish set" + tag);
  writeStorageBuffer(ctx, s.finishSet, s.counters.get(), 0);
  writeStorageBuffer(ctx, s.finishSet, s.indirect.get(), 1);
  writeStorageBuffer(ctx, s.finishSet, s.figures.get(), 2);
}

void ClassifyPass::setCatalog(const vegetation::SpeciesCatalog& catalog) {
  const SpeciesBlock block = packSpecies(catalog);
  std::memcpy(species_.mapped, &block, sizeof(block));
  speciesCount_ = block.count[0];
  kinds_.fill(kNoKind);
  for (size_t i = 0; i < catalog.species.size(); ++i)
    kinds_[i] = catalog.species[i].bare ? kNoKind : static_cast<uint32_t>(catalog.species[i].kind);
}

void ClassifyPass::ensureCapacity(Slot& s, size_t triangles, size_t orderEntries, const RetireBuffer& retire) {
  constexpr VkDeviceSize kNoCeiling = GrowingBuffer::kNoCeiling;
  bool changed = s.triangles.ensure(std::max<size_t>(triangles, 1) * sizeof(SeedTriangleGpu), kNoCeiling, retire);
  changed |= s.visible.ensure(std::max<size_t>(triangles, 1) * sizeof(uint32_t), kNoCeiling, retire);
  changed |= s.order.ensure(std::max<size_t>(orderEntries, 1) * sizeof(uint32_t), kNoCeiling, retire);
  if (changed) s.boundImagery = VK_NULL_HANDLE;  // rewrite the set
}

void ClassifyPass::writeSets(Slot& s, VkImageView imagery, VkImageView companions) {
  writeUniformBuffer(*ctx_, s.classifySet, species_.get(), sizeof(SpeciesBlock), 0);
  writeStorageBuffer(*ctx_, s.classifySet, s.triangles.get(), 1);
  writeStorageBuffer(*ctx_, s.classifySet, s.order.get(), 2);
  writeStorageBuffer(*ctx_, s.classifySet, s.counters.get(), 3);
  writeStorageBuffer(*ctx_, s.classifySet, s.records.get(), 4);
  writeSampledImage(*ctx_, s.classifySet, sampler_.get(), imagery, 5);
  writeStorageBuffer(*ctx_, s.classifySet, s.visible.get(), 6);
  writeSampledImage(*ctx_, s.classifySet, sampler_.get(), companions, 7);
  writeStorageBuffer(*ctx_, s.classifySet, s.canopy.get(), 8);
  s.boundImagery = imagery;
  s.boundCompanions = companions;
}

uint32_t ClassifyPass::dispatchClassify(VkCommandBuffer cmd, const Slot& s, const vegetation::BinnedTriangles& bins,
                                        uint32_t clusterSize, uint32_t companionFlags, bool culled) {
  uint32_t nonEmpty = 0;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, classify_.get());
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, classifyPipelineLayout_.get(), 0, 1, &s.classifySet, 0,
                          nullptr);
  for (const vegetation::PlantBin& bin : bins.bins) {
    if (bin.count == 0) continue;
    ++nonEmpty;
    const uint64_t threads = uint64_t{bin.count} * bin.capacity;
    for (uint64_t base = 0; base < threads; base += uint64_t{kMaxGroupsPerDispatch} * kWorkgroup) {
      const ClassifyPush push{bin.first,
                              bin.count,
                              bin.capacity,
                              clusterSize,
                              static_cast<uint32_t>(base),
                              options_.clustersPerSpecies,
                              culled ? 1u : 0u,
                              fades_ ? 0u : 1u,
                              companionFlags,
                              {},
                              thinning_};
      vkCmdPushConstants(cmd, classifyPipelineLayout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
      const uint64_t groups = std::min<uint64_t>((threads - base + kWorkgroup - 1) / kWorkgroup, kMaxGroupsPerDispatch);
      vkCmdDispatch(cmd, static_cast<uint32_t>(groups), 1, 1);
    }
  }
  return nonEmpty;
}

void ClassifyPass::dispatchFinish(VkCommandBuffer cmd, const Slot& s, uint32_t verticesPerGroup, uint32_t patchMask) {
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);

  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, finish_.get());
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, finishPipelineLayout_.get(), 0, 1, &s.finishSet, 0,
                          nullptr);
  const FinishPush fp{verticesPerGroup, options_.clustersPerSpecies, patchMask};
  vkCmdPushConstants(cmd, finishPipelineLayout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(fp), &fp);
  vkCmdDispatch(cmd, 1, 1, 1);

  // Records and draws to the species pipelines; the figures copy to the host.
  memoryBarrier(
      cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
      VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT |
          VK_PIPELINE_STAGE_2_PRE_RASTERIZATION_SHADERS_BIT | VK_PIPELINE_STAGE_2_HOST_BIT,
      VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_HOST_READ_BIT);
}

VegetationFigures ClassifyPass::record(VkCommandBuffer cmd, int slot, std::span<const SeedTriangleGpu> triangles,
                                       uint32_t clusterSize, VkImageView imagery, VkImageView companions, uint32_t companionFlags,
                                       uint32_t verticesPerGroup, uint32_t patchMask, const RetireBuffer& retire,
                                       const CullHook& cull, const vegetation::CanopyTable* canopy) {
  assert(clusterSize >= 1 && clusterSize <= vegetation::kMaxClusterSize);
  Slot& s = slots_[size_t(slot)];
  VegetationFigures f;
  f.seedTriangles = static_cast<uint32_t>(triangles.size());
  f.thinning = thinning_;

  std::vector<uint32_t> counts(triangles.size());
  for (size_t i = 0; i < triangles.size(); ++i)
    counts[i] = triangles[i].layer < 0 ? 0 : vegetation::classifyItems(triangles[i].v0.w, clusterSize);
  const vegetation::BinnedTriangles bins = vegetation::binTriangles(counts);
  f.clusters = bins.clusters;  // work items: seeds of cluster 0 + further clusters
  f.clusterSlots = bins.slots;

  ensureCapacity(s, triangles.size(), bins.order.size(), retire);
  if (!triangles.empty()) std::memcpy(s.triangles.buffer().mapped, triangles.data(), triangles.size_bytes());
  if (!bins.order.empty())
    std::memcpy(s.order.buffer().mapped, bins.order.data(), bins.order.size() * sizeof(uint32_t));
  // The crowns (the slot's previous frame, which read them, has finished: its fence).
  writeCanopy(s.canopy.mapped, canopy);
  // The slot's previous frame has finished (the renderer waited on its fence): its set is free.
  if (s.boundImagery != imagery || s.boundCompanions != companions) writeSets(s, imagery, companions);

  if (cull && !triangles.empty()) {
    // visible[] is read by the slot's previous classify dispatches (finished: its fence) and
    // written now by the hook; the dispatches below read it.
    cull(cmd, s.triangles.get(), s.visible.get(), static_cast<uint32_t>(triangles.size()));
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
  }

  vkCmdFillBuffer(cmd, s.counters.get(), 0, kCounterBytes, 0);
  // The counters are cleared after the slot's previous draws read its records and indirect args.
  memoryBarrier(
      cmd,
      VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT,
      VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
      VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);

  f.bins = dispatchClassify(cmd, s, bins, clusterSize, companionFlags, cull && !triangles.empty());
  dispatchFinish(cmd, s, verticesPerGroup, patchMask);
  return f;
}

void ClassifyPass::readFigures(int slot, VegetationFigures& f) const {
  const auto* counters = static_cast<const uint32_t*>(slots_[size_t(slot)].figures.mapped);
  f.gpuCounts = true;
  f.groupsTotal = f.plantsTotal = 0;
  for (size_t i = 0; i < kSpeciesSlots; ++i) {
    f.groups[i] = counters[i];
    f.plants[i] = counters[kSpeciesSlots + i];
    f.groupsTotal += f.groups[i];
    f.plantsTotal += f.plants[i];
    if (f.groups[i] > options_.clustersPerSpecies) f.overflow = true;
  }
  f.cullGroupsCulled = counters[2 * kSpeciesSlots];
  f.cullGroupPlantsCulled = counters[2 * kSpeciesSlots + 1];
  for (size_t i = 0; i < kSpeciesSlots; ++i) f.wanted[i] = counters[2 * kSpeciesSlots + 2 + i];
}

void ClassifyPass::updateThinningFromSlot(int slot) {
  if (slot < 0) {
    thinning_.fill(0.0f);
    return;
  }
  const auto* counters = static_cast<const uint32_t*>(slots_[size_t(slot)].figures.mapped);
  for (size_t i = 0; i < kSpeciesSlots; ++i)
    thinning_[i] = vegetation::thinningPressure(counters[2 * kSpeciesSlots + 2 + i], options_.clustersPerSpecies);
}

void ClassifyPass::updateThinning(const VegetationFigures& f) {
  if (!f.gpuCounts) return;
  for (size_t i = 0; i < kSpeciesSlots; ++i)
    thinning_[i] = vegetation::thinningPressure(f.wanted[i], options_.clustersPerSpecies);
}

uint64_t ClassifyPass::gpuBytes() const {
  uint64_t bytes = species_.size;
  for (const Slot& s : slots_)
    bytes += s.triangles.size() + s.order.size() + s.counters.size + s.records.size + s.indirect.size + s.figures.size +
             s.visible.size();
  return bytes;
}

}  // namespace vegstream::render
