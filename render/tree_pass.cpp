// Trees on the GPU (tree_pass.h): pipelines, pool, classify and draws (the models' upload and the
// impostor capture: tree_models.cpp).
#include "render/tree_pass.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>
#include <string>

#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

#include "render/descriptors.h"
#include "render/pipeline_builder.h"
#include "render/render_targets.h"
#include "render/shadow_cascades.h"
#include "render/tree_impostors.h"
#include "render/tree_pass_internal.h"
#include "shaders/tree.frag.h"
#include "shaders/tree_core.frag.h"
#include "shaders/tree.vert.h"
#include "shaders/tree_classify.comp.h"
#include "shaders/tree_sort.comp.h"
#include "shaders/tree_impostor.frag.h"
#include "shaders/tree_impostor.vert.h"
#include "shaders/tree_shadow_raster.comp.h"

namespace vegstream::render {
using namespace tree_detail;
static_assert(kTreeShadowCascades == static_cast<uint32_t>(kShadowCascades));
namespace {

// Workgroups of a cascade's compute rasteriser (one caster each at a time, in as many layers as
// the dispatch has): enough to fill a large GPU's compute units (the H100: 132 × 32 groups of 64).
// A CPU rasteriser runs one workgroup at a time per thread and pays each one's start (its shared
// memory, the models' table built again): there 64. On lavapipe (2 cores) a benchmark-30s
// recording at 160 × 90 took 12 % less CPU than with 4096 groups (the same frames: the map does
// not depend on how the work is shared out, tests/render/tree_shadow_raster_test.cpp).
constexpr uint32_t kShadowGroups = 4096, kShadowGroupsOnCpu = 64;

// Camera-relative frustum planes of a Vulkan clip space (Gribb & Hartmann), normalised.
void frustumPlanes(const glm::dmat4& m, glm::vec4 out[6]) {
  const auto row = [&](int i) { return glm::dvec4(m[0][i], m[1][i], m[2][i], m[3][i]); };
  const glm::dvec4 planes[6] = {row(3) + row(0), row(3) - row(0), row(3) + row(1),
                                row(3) - row(1), row(2),          row(3) - row(2)};
  for (int p = 0; p < 6; ++p) {
    const double len = glm::length(glm::dvec3(planes[p]));
    out[p] = glm::vec4(planes[p] / (len > 0.0 ? len : 1.0));
  }
}

}  // namespace

TreePass::TreePass(const Context& ctx, VkDescriptorSetLayout frameLayout, VkSampleCountFlagBits samples,
                   VkDescriptorSetLayout shadowTargetLayout, uint32_t shadowGroups, uint32_t shadowLayers)
    : ctx_(&ctx), samples_(samples), shadowLayers_(std::min(shadowLayers, 16u)),
      shadowGroups_(shadowGroups > 0      ? std::max(shadowGroups, 16u)
                    : ctx.info().software ? kShadowGroupsOnCpu
                                          : kShadowGroups) {
  const VkShaderStageFlags all =
      VK_SHADER_STAGE_COMPUTE_BIT | VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
  std::vector<VkDescriptorSetLayoutBinding> bindings = {{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, all, nullptr}};
  for (uint32_t b = 1; b <= 7; ++b) bindings.push_back({b, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr});
  // The atlas: albedo and coverage (also read by the shadow cascades' compute rasteriser), normals.
  bindings.push_back({8, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1,
                      VK_SHADER_STAGE_FRAGMENT_BIT | VK_SHADER_STAGE_COMPUTE_BIT, nullptr});
  bindings.push_back({9, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr});
  setLayout_ = createLayout(ctx, bindings, "tree set layout");
  const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, kSlots},
                                        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 7 * kSlots},
                                        {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 2 * kSlots}};
  pool_ = createPool(ctx, sizes, kSlots, "tree pool");
  allocateSlotSets(ctx, pool_.get(), setLayout_.get(), sets_, "tree set");
  sampler_ = createTrilinearClampSampler(ctx, kImpostorMipLevels, "tree impostor sampler");
  createPipelines(frameLayout, shadowTargetLayout);
}

TreePass::~TreePass() = default;

void TreePass::createPipelines(VkDescriptorSetLayout frameLayout, VkDescriptorSetLayout shadowTargetLayout) {
  const VkDescriptorSetLayout sets[] = {frameLayout, setLayout_.get()};
  const VkPushConstantRange classifyPush{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(uint32_t)};
  classifyLayout_ = createPipelineLayout(*ctx_, sets, {&classifyPush, 1}, "tree classify layout");
  classifyPipeline_ = createComputePipeline(*ctx_, classifyLayout_.get(), spv_tree_classify_comp, "tree classify");
  sortPipeline_ = createComputePipeline(*ctx_, classifyLayout_.get(), spv_tree_sort_comp, "tree sort");
  // Every tree casts into the sun's cascades through its impostor seen from the sun, whatever it
  // is drawn as (the models' thousands of alpha-tested cards cost the H200 20 ms a frame in the
  // cascades over the Kolob forest), rasterised in compute (shaders/tree_shadow_raster.comp).
  const VkDescriptorSetLayout shadowSets[] = {frameLayout, setLayout_.get(), shadowTargetLayout};
  const VkPushConstantRange shadowPush{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(TreePush)};
  shadowLayout_ = createPipelineLayout(*ctx_, shadowSets, {&shadowPush, 1}, "tree shadow raster layout");
  shadowPipeline_ =
      createComputePipeline(*ctx_, shadowLayout_.get(), spv_tree_shadow_raster_comp, "tree shadow raster");
  const VkPushConstantRange drawPush{VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(TreePush)};
  drawLayout_ = createPipelineLayout(*ctx_, sets, {&drawPush, 1}, "tree draw layout");

  GraphicsPipelineDesc mesh;
  mesh.name = "tree pipeline";
  mesh.stages = {{VK_SHADER_STAGE_VERTEX_BIT, spv_tree_vert}, {VK_SHADER_STAGE_FRAGMENT_BIT, spv_tree_frag}};
  setTreeVertexInput(mesh);
  mesh.cullMode = VK_CULL_MODE_NONE;  // cards are seen from both sides
  mesh.samples = samples_;
  mesh.colorFormat = kColorFormat;
  mesh.depthFormat = kDepthFormat;
  mesh.layout = drawLayout_.get();
  meshPipeline_ = createGraphicsPipeline(*ctx_, mesh);

  // The crowns' opaque cores (vegetation/tree_core.h), drawn first: closed solids, no alpha test,
  // depth tested and written before shading, so the cards behind them are rejected unshaded.
  GraphicsPipelineDesc core = mesh;
  core.name = "tree core pipeline";
  core.stages = {{VK_SHADER_STAGE_VERTEX_BIT, spv_tree_vert}, {VK_SHADER_STAGE_FRAGMENT_BIT, spv_tree_core_frag}};
  core.cullMode = VK_CULL_MODE_BACK_BIT;
  corePipeline_ = createGraphicsPipeline(*ctx_, core);

  GraphicsPipelineDesc impostor = mesh;
  impostor.name = "tree impostor pipeline";
  impostor.stages = {{VK_SHADER_STAGE_VERTEX_BIT, spv_tree_impostor_vert},
                     {VK_SHADER_STAGE_FRAGMENT_BIT, spv_tree_impostor_frag}};
  impostor.bindings.clear();
  impostor.attributes.clear();
  impostorPipeline_ = createGraphicsPipeline(*ctx_, impostor);
}

uint64_t TreePass::gpuBytes() const {
  uint64_t bytes = vertices_.size + indices_.size + branches_.size + instances_.size + visible_.size + meshDraws_.size +
                   impostorDraws_.size + drawTemplate_.size + counters_.size;
  for (const auto& b : pageCounts_) bytes += b.size;
  for (const auto& b : staging_) bytes += b.size;
  if (impostors_) bytes += impostors_->gpuBytes();
  return bytes;
}

void TreePass::recordPageUploads(VkCommandBuffer cmd, size_t s, const TreeRequest& request,
                                 const RetireBuffer& retire) {
  // Page uploads through the slot's staging buffer (its previous frame has finished).
  VkDeviceSize uploadBytes = 0;
  for (const TreePageUpload& u : request.uploads)
    if (u.page < pageCapacity_) uploadBytes += VkDeviceSize{u.count} * sizeof(TreeInstanceGpu);
  if (uploadBytes > 0) {
    if (staging_[s].size < uploadBytes) {
      if (staging_[s].size > 0) retire(std::move(staging_[s]));
      staging_[s] = createBuffer(*ctx_, grownSize(uploadBytes), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::HostUpload,
                                 "tree page staging");
    }
    std::vector<VkBufferCopy> copies;
    VkDeviceSize at = 0;
    for (const TreePageUpload& u : request.uploads) {
      if (u.page >= pageCapacity_ || u.count == 0) continue;
      const VkDeviceSize bytes = VkDeviceSize{std::min(u.count, kTreePageSize)} * sizeof(TreeInstanceGpu);
      std::memcpy(static_cast<uint8_t*>(staging_[s].mapped) + at, u.instances, static_cast<size_t>(bytes));
      copies.push_back({at, VkDeviceSize{u.page} * kTreePageSize * sizeof(TreeInstanceGpu), bytes});
      at += bytes;
    }
    // Earlier frames' draws read the pool: their vertex stages finish before the copy writes.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                  VK_ACCESS_2_SHADER_STORAGE_READ_BIT, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    vkCmdCopyBuffer(cmd, staging_[s].get(), instances_.get(), static_cast<uint32_t>(copies.size()), copies.data());
  }
}

void TreePass::writeBlock(size_t s, const TreeRequest& request, const glm::dmat4& viewProj, float lodScale,
                          float shadowMarginM, uint32_t pages) {
  auto* block = static_cast<TreeBlock*>(uniforms_[s].mapped);
  block->camera = glm::vec4(static_cast<float>(request.cameraEnu[0]), static_cast<float>(request.cameraEnu[1]),
                            static_cast<float>(request.cameraEnu[2]), request.timeS);
  block->lod = {request.lod.fullHeights * lodScale, request.lod.reducedHeights * lodScale, request.lod.horizonM,
                request.lod.fadeShare};
  frustumPlanes(viewProj, block->frustum);
  block->counts = {pages * kTreePageSize, static_cast<uint32_t>(models_.size()), request.fades ? 1u : 0u,
                   kImpostorViews};
  block->capacity = {capacity_[0], capacity_[1], capacity_[2], 0u};
  block->limits = glm::vec4(shadowMarginM, request.lod.impostorEndHeights * lodScale, request.lod.nearFadeM, 0.0f);
  block->casters = {casterCapacity_[0], casterCapacity_[1], casterCapacity_[2], 0u};
  std::memcpy(block->models, modelBlock_.data(), modelBlock_.size());
}

void TreePass::recordClassify(VkCommandBuffer cmd, int slot, VkDescriptorSet frameSet, const TreeRequest& request,
                              const glm::dmat4& viewProj, float lodScale, float shadowMarginM,
                              const RetireBuffer& retire) {
  const auto s = static_cast<size_t>(slot);
  slotRecorded_[s] = false;
  if (models_.empty() || pageCapacity_ == 0) return;
  recordPageUploads(cmd, s, request, retire);
  const auto pages = static_cast<uint32_t>(std::min<size_t>(request.pageCounts.size(), pageCapacity_));
  auto* counts = static_cast<uint32_t*>(pageCounts_[s].mapped);
  std::memcpy(counts, request.pageCounts.data(), pages * sizeof(uint32_t));
  slotPages_[s] = pages;

  writeBlock(s, request, viewProj, lodScale, shadowMarginM, pages);

  // Reset the draws and counters, classify, clamp.
  const VkBufferCopy meshCopy{0, 0, meshDraws_.size};
  const VkBufferCopy impostorCopy{meshDraws_.size, 0, impostorDraws_.size};
  memoryBarrier(cmd,
                VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT |
                    VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT,
                VK_PIPELINE_STAGE_2_COPY_BIT | VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  vkCmdCopyBuffer(cmd, drawTemplate_.get(), meshDraws_.get(), 1, &meshCopy);
  vkCmdCopyBuffer(cmd, drawTemplate_.get(), impostorDraws_.get(), 1, &impostorCopy);
  vkCmdFillBuffer(cmd, counters_.get(), 0, VK_WHOLE_SIZE, 0);
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT | VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, classifyPipeline_.get());
  const VkDescriptorSet bound[] = {frameSet, sets_[s]};
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, classifyLayout_.get(), 0, 2, bound, 0, nullptr);
  uint32_t mode = 0;
  vkCmdPushConstants(cmd, classifyLayout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(mode), &mode);
  if (pages > 0) vkCmdDispatch(cmd, pages, 1, 1);  // 256 threads = one page per group
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  mode = 1;
  vkCmdPushConstants(cmd, classifyLayout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(mode), &mode);
  vkCmdDispatch(cmd, (static_cast<uint32_t>(models_.size()) + 255) / 256, 1, 1);
  // The near lists front to back (shaders/tree_sort.comp): one group per model and mesh level.
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, sortPipeline_.get());
  vkCmdDispatch(cmd, 2 * static_cast<uint32_t>(models_.size()), 1, 1);
  memoryBarrier(
      cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
      VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_COPY_BIT |
          VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
      VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT);
  const VkBufferCopy countersCopy{0, 0, kCounters * sizeof(uint32_t)};
  vkCmdCopyBuffer(cmd, counters_.get(), readback_[s].get(), 1, &countersCopy);
  hostReadBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  slotRecorded_[s] = true;
  slotCores_[s] = request.cores;
}

void TreePass::recordDraw(VkCommandBuffer cmd, int slot, VkDescriptorSet frameSet) {
  const auto s = static_cast<size_t>(slot);
  if (!slotRecorded_[s]) return;
  const VkDescriptorSet bound[] = {frameSet, sets_[s]};
  const VkShaderStageFlags stages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
  const auto count = static_cast<uint32_t>(models_.size());
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, corePipeline_.get());
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, drawLayout_.get(), 0, 2, bound, 0, nullptr);
  const VkDeviceSize offset = 0;
  const VkBuffer vb = vertices_.get();
  vkCmdBindVertexBuffers(cmd, 0, 1, &vb, &offset);
  vkCmdBindIndexBuffer(cmd, indices_.get(), 0, VK_INDEX_TYPE_UINT32);
  // The crowns' cores first (opaque, early depth): the cards behind them are rejected unshaded.
  for (uint32_t lod = 0; lod < (slotCores_[s] ? 2u : 0u); ++lod)
    for (uint32_t m = 0; m < count; ++m) {
      const TreePush push{glm::mat4(1.0f), m, lod, 0u, static_cast<uint32_t>(samples_)};
      vkCmdPushConstants(cmd, drawLayout_.get(), stages, 0, sizeof(push), &push);
      vkCmdDrawIndexedIndirect(cmd, meshDraws_.get(), (2 * count + m * 2 + lod) * kIndexedCommand, 1,
                               static_cast<uint32_t>(kIndexedCommand));
    }
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, meshPipeline_.get());
  // Nearest first: every model's full trees, then the reduced ones, then the impostors, so the
  // depth the near crowns write lets the hardware reject what they hide.
  // (Measured on the H200 at the Kolob forest's edge: 8.16 ms against 8.60 model by model.)
  for (uint32_t lod = 0; lod < 2; ++lod)
    for (uint32_t m = 0; m < models_.size(); ++m) {
      const TreePush push{glm::mat4(1.0f), m, lod, 0u, static_cast<uint32_t>(samples_)};
      vkCmdPushConstants(cmd, drawLayout_.get(), stages, 0, sizeof(push), &push);
      vkCmdDrawIndexedIndirect(cmd, meshDraws_.get(), (m * 2 + lod) * kIndexedCommand, 1,
                               static_cast<uint32_t>(kIndexedCommand));
    }
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, impostorPipeline_.get());
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, drawLayout_.get(), 0, 2, bound, 0, nullptr);
  for (uint32_t m = 0; m < count; ++m) {
    const TreePush push{glm::mat4(1.0f), m, 2u, 0u, static_cast<uint32_t>(samples_)};
    vkCmdPushConstants(cmd, drawLayout_.get(), stages, 0, sizeof(push), &push);
    vkCmdDrawIndexedIndirect(cmd, impostorDraws_.get(), m * kIndexedCommand, 1, static_cast<uint32_t>(kIndexedCommand));
  }
}

void TreePass::recordShadow(VkCommandBuffer cmd, int slot, VkDescriptorSet frameSet, int cascade,
                            const glm::mat4& matrix, float texelM, VkDescriptorSet target) {
  const auto s = static_cast<size_t>(slot);
  if (!slotRecorded_[s]) return;
  const VkDescriptorSet bound[] = {frameSet, sets_[s], target};
  const auto c = static_cast<uint32_t>(cascade);
  assert(c < kTreeShadowCascades);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, shadowPipeline_.get());
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, shadowLayout_.get(), 0, 3, bound, 0, nullptr);
  const TreePush push{matrix, 0u, c, 1u, 1u};  // lod: the cascade (the layer)
  vkCmdPushConstants(cmd, shadowLayout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
  // Groups that take the casters (the classify's box test) in turns, in as many layers as a
  // crown's size in texels asks for: the layers take a caster's blocks in turns (a 20 m tree is
  // about 300 blocks of 8 × 8 texels in a 0.08 m cascade, one or two in a 1.2 m one).
  const auto layers = shadowLayers_ > 0
                          ? shadowLayers_
                          : static_cast<uint32_t>(std::clamp(std::lround(0.8f / std::max(texelM, 1e-3f)), 1L, 16L));
  vkCmdDispatch(cmd, shadowGroups_ / layers, 1, layers);
}

uint32_t TreePass::regionBase(uint32_t m, uint32_t lod) const {
  const uint32_t perModel = capacity_[0] + capacity_[1] + capacity_[2];
  return m * perModel + (lod >= 1 ? capacity_[0] : 0u) + (lod >= 2 ? capacity_[1] : 0u);
}

std::vector<uint32_t> TreePass::readList(uint32_t model, uint32_t lod) const {
  assert(model < models_.size() && lod < 2);
  const VkDeviceSize region = VkDeviceSize{regionBase(model, lod)} * sizeof(glm::uvec4);
  const VkDeviceSize listBytes = VkDeviceSize{capacity_[lod]} * sizeof(glm::uvec4);
  GpuBuffer host = createBuffer(*ctx_, kIndexedCommand + listBytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                MemoryUse::HostReadback, "tree list read-back");
  ctx_->submitAndWait([&](VkCommandBuffer cmd) {
    const VkBufferCopy command{(model * 2 + lod) * kIndexedCommand, 0, kIndexedCommand};
    const VkBufferCopy list{region, kIndexedCommand, listBytes};
    vkCmdCopyBuffer(cmd, meshDraws_.get(), host.get(), 1, &command);
    vkCmdCopyBuffer(cmd, visible_.get(), host.get(), 1, &list);
    hostReadBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  });
  const auto* words = static_cast<const uint32_t*>(host.mapped);
  const uint32_t count = std::min(words[1], capacity_[lod]);  // the command's instance count
  const auto* entries = reinterpret_cast<const glm::uvec4*>(static_cast<const uint8_t*>(host.mapped) + kIndexedCommand);
  std::vector<uint32_t> out(count);
  for (uint32_t i = 0; i < count; ++i) out[i] = entries[i].x;
  return out;
}

TreeFigures TreePass::figures(int slot) const {
  TreeFigures f;
  const auto s = static_cast<size_t>(slot);
  if (!slotRecorded_[s]) return f;
  const auto* c = static_cast<const uint32_t*>(readback_[s].mapped);
  f.pages = slotPages_[s];
  f.instances = c[0];
  f.full = c[1];
  f.reduced = c[2];
  f.impostor = c[3];
  f.dropped = c[4];
  for (uint32_t k = 0; k < kTreeShadowCascades; ++k) f.shadowCasters[k] = c[5 + k];
  f.gpuCounts = true;
  return f;
}

}  // namespace vegstream::render
