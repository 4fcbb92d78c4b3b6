// Hi-Z occlusion culling (hiz_pass.h): Greene, Kass & Miller 1993, hierarchical Z-buffer.
#include "render/hiz_pass.h"

#include <algorithm>
#include <cstring>
#include <string>

#include "render/descriptors.h"
#include "render/pipeline_builder.h"
#include "render/vk_check.h"
#include "shaders/hiz_cull.comp.h"
#include "shaders/hiz_depth.comp.h"
#include "shaders/hiz_depth_buffer.comp.h"
#include "shaders/hiz_depth_ms.comp.h"
#include "shaders/hiz_reduce.comp.h"

namespace vegstream::render {
namespace {

constexpr uint32_t kTile = 8;        // hiz_depth / hiz_reduce local size (8 × 8)
constexpr uint32_t kCullGroup = 64;  // hiz_cull local size
constexpr VkDeviceSize kCounterBytes = 4 * sizeof(uint32_t);

struct DepthPush {
  uint32_t width, height, levelW, levelH, samples;
};
struct ReducePush {
  uint32_t srcOffset, srcW, srcH, dstOffset, dstW, dstH;
};
struct CullPush {  // shaders/hiz_cull.comp
  uint32_t count, clusterSize, shadows, width, height, levels, species, drawn;
  std::array<float, vegetation::kMaxSpecies> reach;
};
static_assert(sizeof(CullPush) == 96 && sizeof(CullPush) <= 128, "push constants: 128 bytes guaranteed");

uint32_t groups(uint32_t n, uint32_t size) { return (n + size - 1) / size; }

VkDescriptorSetLayoutBinding binding(uint32_t b, VkDescriptorType type) {
  return {b, type, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
}

}  // namespace

std::vector<HizLevel> hizLevels(VkExtent2D extent) {
  std::vector<HizLevel> levels;
  uint32_t offset = 0;
  for (uint32_t l = 0;; ++l) {
    const uint32_t w = (extent.width + (2u << l) - 1) >> (l + 1), h = (extent.height + (2u << l) - 1) >> (l + 1);
    levels.push_back({w, h, offset});
    offset += w * h;
    if (w == 1 && h == 1) break;
  }
  return levels;
}

std::array<float, vegetation::kMaxSpecies> speciesReach(const vegetation::SpeciesCatalog& catalog) {
  // Blades and stems reach their height from the root (the solved shapes are unit length);
  // sideways, a blade is half its width, a stone ~1 × its size (≤ height + width), a flower
  // head 2.5 widths at the tip (3.6 at its corners), a marker (any kind: trees, and every
  // species in the markers style) 1.5 widths or 0.15 heights. 5 % more covers the shaders'
  // float maths.
  std::array<float, vegetation::kMaxSpecies> reach;
  reach.fill(-1.0f);
  for (size_t i = 0; i < catalog.species.size() && i < reach.size(); ++i) {
    const vegetation::Species& s = catalog.species[i];
    if (s.bare) continue;
    const float side = s.kind == vegetation::RendererKind::Flowers ? 3.6f * s.widthM.max : 1.5f * s.widthM.max;
    reach[i] = 1.05f * (s.heightM.max + std::max(side, 0.15f * s.heightM.max));
  }
  return reach;
}

void HizPass::setCatalog(const vegetation::SpeciesCatalog& catalog) {
  reach_ = speciesReach(catalog);
  speciesCount_ = static_cast<uint32_t>(std::min<size_t>(catalog.species.size(), reach_.size()));
}

HizPass::HizPass(const Context& ctx, VkDescriptorSetLayout frameLayout, const RenderTargets& targets,
                 VkBuffer terrainDepth)
    : ctx_(&ctx), targets_(&targets), levels_(hizLevels(targets.extent())),
      fromBuffer_(terrainDepth != VK_NULL_HANDLE) {
  const uint32_t texels = levels_.back().offset + 1;
  pyramid_ = createBuffer(ctx, VkDeviceSize{texels} * sizeof(float),
                          VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::DeviceLocal,
                          "hi-z pyramid");

  const VkDescriptorSetLayoutBinding depthBindings[] = {
      binding(0, fromBuffer_ ? VK_DESCRIPTOR_TYPE_STORAGE_BUFFER : VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE),
      binding(1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER)};
  depthLayout_ = createLayout(ctx, depthBindings, "hi-z depth set layout");
  const VkDescriptorSetLayoutBinding reduceBindings[] = {binding(0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER)};
  reduceLayout_ = createLayout(ctx, reduceBindings, "hi-z reduce set layout");
  const VkDescriptorSetLayoutBinding cullBindings[] = {
      binding(0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER), binding(1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER),
      binding(2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER), binding(3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER)};
  cullLayout_ = createLayout(ctx, cullBindings, "hi-z cull set layout");
  const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, 1},
                                        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 3 + 4 * kSlots}};
  pool_ = createPool(ctx, sizes, 2 + kSlots, "hi-z pool");

  createPipelines(frameLayout, targets);
  createSets(terrainDepth, targets);
}

void HizPass::createPipelines(VkDescriptorSetLayout frameLayout, const RenderTargets& targets) {
  const Context& ctx = *ctx_;
  const VkPushConstantRange depthPush{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(DepthPush)};
  const VkDescriptorSetLayout dl[] = {depthLayout_.get()};
  depthPipelineLayout_ = createPipelineLayout(ctx, dl, {&depthPush, 1}, "hi-z depth pipeline layout");
  depth_ = createComputePipeline(ctx, depthPipelineLayout_.get(),
                                 fromBuffer_              ? std::span<const uint32_t>(spv_hiz_depth_buffer_comp)
                                 : targets.multisampled() ? std::span<const uint32_t>(spv_hiz_depth_ms_comp)
                                                          : std::span<const uint32_t>(spv_hiz_depth_comp),
                                 "hi-z depth pipeline");
  const VkPushConstantRange reducePush{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(ReducePush)};
  const VkDescriptorSetLayout rl[] = {reduceLayout_.get()};
  reducePipelineLayout_ = createPipelineLayout(ctx, rl, {&reducePush, 1}, "hi-z reduce pipeline layout");
  reduce_ = createComputePipeline(ctx, reducePipelineLayout_.get(), spv_hiz_reduce_comp, "hi-z reduce pipeline");
  const VkPushConstantRange cullPush{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(CullPush)};
  const VkDescriptorSetLayout cl[] = {frameLayout, cullLayout_.get()};
  cullPipelineLayout_ = createPipelineLayout(ctx, cl, {&cullPush, 1}, "hi-z cull pipeline layout");
  cull_ = createComputePipeline(ctx, cullPipelineLayout_.get(), spv_hiz_cull_comp, "hi-z cull pipeline");
}

void HizPass::createSets(VkBuffer terrainDepth, const RenderTargets& targets) {
  const Context& ctx = *ctx_;
  // The depth attachment (every MSAA sample), sampled in SHADER_READ_ONLY_OPTIMAL by recordBuild.
  depthSet_ = allocateDescriptorSet(ctx, pool_.get(), depthLayout_.get(), "hi-z depth set");
  if (fromBuffer_) {
    writeStorageBuffer(ctx, depthSet_, terrainDepth, 0);
  } else {
    writeSeparateImage(ctx, depthSet_, targets.depthAttachment().view.get(), 0);
  }
  writeStorageBuffer(ctx, depthSet_, pyramid_.get(), 1);
  reduceSet_ = allocateDescriptorSet(ctx, pool_.get(), reduceLayout_.get(), "hi-z reduce set");
  writeStorageBuffer(ctx, reduceSet_, pyramid_.get(), 0);

  for (int i = 0; i < kSlots; ++i) {
    Slot& s = slots_[size_t(i)];
    const std::string tag = " (slot " + std::to_string(i) + ")";
    s.counters = createBuffer(ctx, kCounterBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                              MemoryUse::HostReadback, "hi-z cull counters" + tag);
    std::memset(s.counters.mapped, 0, kCounterBytes);
    s.cullSet = allocateDescriptorSet(ctx, pool_.get(), cullLayout_.get(), "hi-z cull set" + tag);
    writeStorageBuffer(ctx, s.cullSet, s.counters.get(), 2);
    writeStorageBuffer(ctx, s.cullSet, pyramid_.get(), 3);
  }
}

void HizPass::recordBuild(VkCommandBuffer cmd) {
  const GpuImage& depth = targets_->depthAttachment();
  const VkExtent2D extent = targets_->extent();
  // The terrain's depth writes → sampled by compute. The image keeps its contents. (From the
  // compute raster's buffer, its own barrier has made the samples readable.)
  if (!fromBuffer_)
    transitionImage(cmd, depth.get(), depth.aspect, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                    VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                    VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                    VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  // The previous frame's tests (either slot; the classify's, the impostors' vertex stage) read
  // the pyramid this build overwrites.
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT,
                VK_ACCESS_2_SHADER_STORAGE_READ_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);

  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, depth_.get());
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, depthPipelineLayout_.get(), 0, 1, &depthSet_, 0,
                          nullptr);
  const DepthPush dp{extent.width, extent.height, levels_[0].width, levels_[0].height,
                     static_cast<uint32_t>(targets_->samples())};
  vkCmdPushConstants(cmd, depthPipelineLayout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(dp), &dp);
  vkCmdDispatch(cmd, groups(levels_[0].width, kTile), groups(levels_[0].height, kTile), 1);

  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, reduce_.get());
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, reducePipelineLayout_.get(), 0, 1, &reduceSet_, 0,
                          nullptr);
  for (size_t l = 1; l < levels_.size(); ++l) {
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                  VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    const HizLevel &src = levels_[l - 1], &dst = levels_[l];
    const ReducePush rp{src.offset, src.width, src.height, dst.offset, dst.width, dst.height};
    vkCmdPushConstants(cmd, reducePipelineLayout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(rp), &rp);
    vkCmdDispatch(cmd, groups(dst.width, kTile), groups(dst.height, kTile), 1);
  }
  // The pyramid → the tests (and tests' copies); the depth back to an attachment for the
  // plants' scope, which loads it.
  memoryBarrier(
      cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_COPY_BIT,
      VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT);
  if (fromBuffer_) return;
  transitionImage(cmd, depth.get(), depth.aspect, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                  VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                  VK_ACCESS_2_SHADER_SAMPLED_READ_BIT,
                  VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                  VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
}

void HizPass::recordCull(VkCommandBuffer cmd, int slot, VkDescriptorSet frameSet, VkBuffer triangles, VkBuffer visible,
                         uint32_t count, uint32_t clusterSize, bool shadows, uint32_t drawn) {
  Slot& s = slots_[size_t(slot)];
  // The slot's previous frame has finished (the renderer waited on its fence): its set is free.
  if (s.boundTriangles != triangles || s.boundVisible != visible) {
    writeStorageBuffer(*ctx_, s.cullSet, triangles, 0);
    writeStorageBuffer(*ctx_, s.cullSet, visible, 1);
    s.boundTriangles = triangles;
    s.boundVisible = visible;
  }
  vkCmdFillBuffer(cmd, s.counters.get(), 0, kCounterBytes, 0);
  // ALL_TRANSFER: the fill counts as a clear (spec) or a copy (some validation layers).
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, cull_.get());
  const VkDescriptorSet sets[] = {frameSet, s.cullSet};
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, cullPipelineLayout_.get(), 0, 2, sets, 0, nullptr);
  const VkExtent2D extent = targets_->extent();
  const CullPush cp{count,         clusterSize,   shadows ? 1u : 0u,
                    extent.width,  extent.height, static_cast<uint32_t>(levels_.size()),
                    speciesCount_, drawn,         reach_};
  vkCmdPushConstants(cmd, cullPipelineLayout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(cp), &cp);
  // One dispatch holds 65535 × 64 ≈ 4 M triangles: far more than a frame's seed triangles.
  vkCmdDispatch(cmd, std::min(groups(count, kCullGroup), 65535u), 1, 1);
  hostReadBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
}

void HizPass::readFigures(int slot, VegetationFigures& f) const {
  const auto* c = static_cast<const uint32_t*>(slots_[size_t(slot)].counters.mapped);
  f.occlusionCulling = true;
  f.cullTested = c[0];
  f.cullCulled = c[1];
  f.cullClustersCulled = c[2];
  f.cullPlantsCulled = c[3];
}

uint64_t HizPass::gpuBytes() const {
  uint64_t bytes = pyramid_.size;
  for (const Slot& s : slots_) bytes += s.counters.size;
  return bytes;
}

}  // namespace vegstream::render
