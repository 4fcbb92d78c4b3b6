// Trees on the GPU (tree_pass.h): the models' upload — vertices, indices (bark and cards, then the
// crowns' cores), branches —, the per-model draw templates, the visible lists and the instance pool
// within the budget, and the impostors captured from the models (render/tree_impostors.h).
#include <algorithm>
#include <bit>
#include <cstring>
#include <string>

#include <glm/geometric.hpp>

#include "render/descriptors.h"
#include "render/impostor_atlas_file.h"
#include "render/tree_impostors.h"
#include "render/tree_pass.h"
#include "render/tree_impostor_outline.h"
#include "render/tree_pass_internal.h"
#include "shaders/tree.frag.h"
#include "shaders/tree.vert.h"

namespace vegstream::render {
using namespace tree_detail;

// The models of every set (at most kMaxTreeModels) in one mesh, in order.
struct TreePass::PackedModels {
  std::vector<vegetation::TreeVertex> vertices;
  // The impostors' one triangle (shaders/tree_impostor.vert), first.
  std::vector<uint32_t> indices = {0u, 1u, 2u};
  std::vector<vegetation::TreeBranch> branches;
  std::vector<TreeImpostorModel> impostorModels;
};

// Packs the models' levels into one vertex and index array, their branches into one, and fills
// models_ and each model's GPU record in modelBlock_.
TreePass::PackedModels TreePass::packModels(std::span<const TreeModelSet> sets) {
  PackedModels p;
  auto* gpuModels = reinterpret_cast<TreeModelGpu*>(modelBlock_.data());
  for (const TreeModelSet& set : sets)
    for (const vegetation::TreeModel& model : set.variants) {
      if (models_.size() == kMaxTreeModels) break;
      const auto m = static_cast<uint32_t>(models_.size());
      ModelDraw draw{};
      for (int lod = 0; lod < 2; ++lod) {
        draw.firstIndex[lod] = static_cast<uint32_t>(p.indices.size());
        draw.indexCount[lod] = model.lod[lod].coreFirstIndex;
        draw.coreCount[lod] = static_cast<uint32_t>(model.lod[lod].indices.size()) - model.lod[lod].coreFirstIndex;
        draw.vertexOffset[lod] = static_cast<uint32_t>(p.vertices.size());
        p.indices.insert(p.indices.end(), model.lod[lod].indices.begin(), model.lod[lod].indices.end());
        p.vertices.insert(p.vertices.end(), model.lod[lod].vertices.begin(), model.lod[lod].vertices.end());
      }
      // The impostor's square holds the model seen from any direction: its bounding sphere
      // about the centre.
      const float centreZ = 0.5f * model.modelHeightM;
      float radius = 0.0f;
      for (const auto& v : model.lod[0].vertices)
        radius = std::max(radius, glm::length(glm::vec3(v.position[0], v.position[1], v.position[2] - centreZ)));
      p.impostorModels.push_back({centreZ, 1.02f * radius});
      TreeModelGpu& g = gpuModels[m];
      g.mesh0 = {draw.firstIndex[0], draw.indexCount[0], draw.vertexOffset[0], static_cast<uint32_t>(p.branches.size())};
      g.mesh1 = {draw.firstIndex[1], draw.indexCount[1], draw.vertexOffset[1], m};
      g.shape = {model.modelHeightM, std::max(model.crownRadiusM, 0.1f), 1.02f * radius, centreZ};
      const ImpostorTriangle triangle =
          impostorTriangle(model.lod[0].vertices, {g.shape.x, g.shape.y, g.shape.z, g.shape.w});
      g.triangleApex = triangle.apex;
      g.triangleBase = triangle.base;
      g.ids = {set.species, std::bit_cast<uint32_t>(std::max(model.crownAreaRadiusM, 0.1f)), 0u, 0u};
      g.leaf = {set.params.leafColour[0], set.params.leafColour[1], set.params.leafColour[2], set.params.translucency};
      g.bark = {set.params.barkColour[0], set.params.barkColour[1], set.params.barkColour[2],
                set.params.form == vegetation::TreeForm::Broadleaf ? 1.0f : 0.0f};
      p.branches.insert(p.branches.end(), model.branches.begin(), model.branches.end());
      models_.push_back(draw);
    }
  return p;
}

VkDeviceSize TreePass::createDrawBuffers(uint32_t count) {
  const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  // Visible lists: per model the trees it may draw at each level (a cross-fading tree in two);
  // then per cascade and model the sun's shadow casters (the near cascades cover less ground).
  capacity_ = {2048u, 8192u, 65536u};
  casterCapacity_ = {4096u, 16384u, 65536u};
  const uint32_t perModel = capacity_[0] + capacity_[1] + capacity_[2];
  const VkDeviceSize visibleBytes =
      VkDeviceSize{count} * (perModel + casterCapacity_[0] + casterCapacity_[1] + casterCapacity_[2]) *
      sizeof(glm::uvec4);
  visible_ = createBuffer(*ctx_, visibleBytes, storage | VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::DeviceLocal,
                         "tree visible lists");  // transfer source: readList (tests)
  // The draws and their per-frame template (instance counts 0, firsts at the regions).
  std::vector<uint32_t> tmpl;
  // Per model and level: bark and cards, then (a second set) the crowns' cores of the same
  // lists, their instance counts copied by the classify's finish.
  for (const bool cores : {false, true})
    for (uint32_t m = 0; m < count; ++m)
      for (int lod = 0; lod < 2; ++lod) {
        const ModelDraw& d = models_[m];
        const uint32_t base = regionBase(m, static_cast<uint32_t>(lod));
        tmpl.insert(tmpl.end(), {cores ? d.coreCount[lod] : d.indexCount[lod], 0u,
                                 d.firstIndex[lod] + (cores ? d.indexCount[lod] : 0u), d.vertexOffset[lod], base});
      }
  // The impostor draws (shaders/common/tree_layout.glsl treeCasterCommand): per model the
  // impostors, then per cascade and model the shadow casters, each the triangle's three indices; the
  // classify counts their instances.
  for (uint32_t m = 0; m < count; ++m)
    tmpl.insert(tmpl.end(), {kImpostorIndices, 0u, 0u, 0u, regionBase(m, 2)});
  uint32_t casterBase = count * perModel;
  for (uint32_t c = 0; c < kTreeShadowCascades; ++c)
    for (uint32_t m = 0; m < count; ++m) {
      tmpl.insert(tmpl.end(), {kImpostorIndices, 0u, 0u, 0u, casterBase});
      casterBase += casterCapacity_[c];
    }
  drawTemplate_ = createBufferWithData(*ctx_, tmpl.data(), tmpl.size() * sizeof(uint32_t),
                                       VK_BUFFER_USAGE_TRANSFER_SRC_BIT, "tree draw template");
  const VkBufferUsageFlags draws =
      storage | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
  meshDraws_ = createBuffer(*ctx_, count * 4 * kIndexedCommand, draws, MemoryUse::DeviceLocal, "tree mesh draws");
  impostorDraws_ = createBuffer(*ctx_, count * (1 + kTreeShadowCascades) * kIndexedCommand,
                                draws, MemoryUse::DeviceLocal,
                                "tree impostor draws");
  counters_ = createBuffer(*ctx_, kCounters * sizeof(uint32_t),
                           storage | VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                           MemoryUse::DeviceLocal, "tree counters");
  return visibleBytes;
}

bool TreePass::createInstancePool(uint64_t fixedBytes, uint64_t budgetBytes, uint32_t count) {
  const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  uint64_t fixed = fixedBytes;
  // Per-slot host buffers; the pool from what the budget leaves.
  for (int s = 0; s < kSlots; ++s) {
    uniforms_[size_t(s)] = createBuffer(*ctx_, sizeof(TreeBlock), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                                        MemoryUse::HostUpload, "tree block (slot " + std::to_string(s) + ")");
    readback_[size_t(s)] = createBuffer(*ctx_, kCounters * sizeof(uint32_t), VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                        MemoryUse::HostReadback, "tree counters read-back");
    slotRecorded_[size_t(s)] = false;
  }
  fixed += drawTemplate_.size + meshDraws_.size + impostorDraws_.size;
  fixed += VkDeviceSize{count} * 2 * kImpostorViews * kImpostorCellPx * kImpostorViews * kImpostorCellPx * 4 +
           VkDeviceSize{kImpostorViews} * kImpostorCellPx * kImpostorViews * kImpostorCellPx * 4;
  const uint64_t pageBytes = uint64_t{kTreePageSize} * sizeof(TreeInstanceGpu) + kSlots * sizeof(uint32_t);
  if (fixed >= budgetBytes) return false;
  pageCapacity_ = static_cast<uint32_t>(std::min<uint64_t>((budgetBytes - fixed) / pageBytes, kMaxPages));
  if (pageCapacity_ == 0) return false;
  instances_ = createBuffer(*ctx_, VkDeviceSize{pageCapacity_} * kTreePageSize * sizeof(TreeInstanceGpu),
                            storage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::DeviceLocal, "tree instances");
  for (int s = 0; s < kSlots; ++s) {
    pageCounts_[size_t(s)] = createBuffer(*ctx_, VkDeviceSize{pageCapacity_} * sizeof(uint32_t),
                                          VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::HostUpload,
                                          "tree page counts (slot " + std::to_string(s) + ")");
    std::memset(pageCounts_[size_t(s)].mapped, 0, pageCounts_[size_t(s)].size);
    slotPages_[size_t(s)] = 0;
  }
  return true;
}

void TreePass::writeSlotSet(size_t s) {
  const VkDescriptorSet set = sets_[s];
  writeUniformBuffer(*ctx_, set, uniforms_[s].get(), sizeof(TreeBlock), 0);
  writeStorageBuffer(*ctx_, set, instances_.get(), 1);
  writeStorageBuffer(*ctx_, set, visible_.get(), 2);
  writeStorageBuffer(*ctx_, set, branches_.get(), 3);
  writeStorageBuffer(*ctx_, set, pageCounts_[s].get(), 4);
  writeStorageBuffer(*ctx_, set, meshDraws_.get(), 5);
  writeStorageBuffer(*ctx_, set, impostorDraws_.get(), 6);
  writeStorageBuffer(*ctx_, set, counters_.get(), 7);
}

// The impostors, captured with the model pipeline in capture mode (2 attachments, 1 sample);
// then every slot's set (the atlas bindings first need an atlas: captured here with set 0).
void TreePass::captureImpostors(std::span<const TreeImpostorModel> impostorModels, VkDescriptorSet frameSet) {
  GraphicsPipelineDesc capture;
  capture.name = "tree impostor capture pipeline";
  capture.stages = {{VK_SHADER_STAGE_VERTEX_BIT, spv_tree_vert}, {VK_SHADER_STAGE_FRAGMENT_BIT, spv_tree_frag}};
  setTreeVertexInput(capture);
  capture.cullMode = VK_CULL_MODE_NONE;
  capture.samples = kImpostorSamples;
  capture.colorFormat = VK_FORMAT_R8G8B8A8_UNORM;
  capture.colorAttachments = 2;
  capture.depthFormat = VK_FORMAT_D32_SFLOAT;
  capture.layout = drawLayout_.get();
  Pipeline capturePipeline = createGraphicsPipeline(*ctx_, capture);

  // The capture reads the models from slot 0's block.
  auto* block0 = static_cast<TreeBlock*>(uniforms_[0].mapped);
  std::memset(block0, 0, sizeof(TreeBlock));
  std::memcpy(block0->models, modelBlock_.data(), modelBlock_.size());
  writeSlotSet(0);
  // A placeholder atlas for the capture's own set (the capture does not sample it).
  GpuImage placeholder = createImageArray(*ctx_, {1, 1}, 1, VK_FORMAT_R8G8B8A8_UNORM,
                                          VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                                          "tree atlas placeholder");
  ctx_->submitAndWait([&](VkCommandBuffer cmd) {
    transitionImageRange(cmd, placeholder.get(), {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1}, VK_IMAGE_LAYOUT_UNDEFINED,
                         VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, 0,
                         VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  });
  writeSampledImage(*ctx_, sets_[0], sampler_.get(), placeholder.view.get(), 8);
  writeSampledImage(*ctx_, sets_[0], sampler_.get(), placeholder.view.get(), 9);
  impostors_ = std::make_unique<TreeImpostors>(
      *ctx_, impostorModels, [&](VkCommandBuffer cmd, uint32_t m) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, capturePipeline.get());
        const VkDescriptorSet bound[] = {frameSet, sets_[0]};
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, drawLayout_.get(), 0, 2, bound, 0, nullptr);
        const VkDeviceSize offset = 0;
        const VkBuffer vb = vertices_.get();
        vkCmdBindVertexBuffers(cmd, 0, 1, &vb, &offset);
        vkCmdBindIndexBuffer(cmd, indices_.get(), 0, VK_INDEX_TYPE_UINT32);
        const TreePush push{glm::mat4(1.0f), m, kImpostorViews, 2u, static_cast<uint32_t>(kImpostorSamples)};
        vkCmdPushConstants(cmd, drawLayout_.get(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                           sizeof(push), &push);
        // The whole Full model, its core too (what shows between the cards).
        vkCmdDrawIndexed(cmd, models_[m].indexCount[0] + models_[m].coreCount[0], kImpostorViews * kImpostorViews,
                         models_[m].firstIndex[0],
                         static_cast<int32_t>(models_[m].vertexOffset[0]), 0);
      });
}

std::string TreePass::impostorKey(const PackedModels& p) const {
  ImpostorKey key;
  key.add("vegstream tree impostors: tree.vert, tree.frag in capture mode");
  key.addValues(std::span(spv_tree_vert));
  key.addValues(std::span(spv_tree_frag));
  const uint32_t layout[] = {kImpostorViews, kImpostorCellPx, kImpostorMipLevels,
                             static_cast<uint32_t>(kImpostorSamples), sizeof(vegetation::TreeVertex)};
  key.addValues(std::span(layout));
  // The device and driver that rasterise it.
  const VkPhysicalDeviceProperties& d = ctx_->properties();
  const uint32_t device[] = {d.vendorID, d.deviceID, d.driverVersion, d.apiVersion};
  key.addValues(std::span(device));
  key.addValues(std::span(d.pipelineCacheUUID));
  key.add(std::string_view(d.deviceName));
  key.add(ctx_->info().driver);
  // What the capture reads: the models' records, vertices, indices, draws and cells.
  key.addValues(std::span(modelBlock_));
  key.addValues(std::span(p.vertices));
  key.addValues(std::span(p.indices));
  for (const ModelDraw& m : models_) key.addValue(m);
  key.addValues(std::span(p.impostorModels));
  return key.finish();
}

void TreePass::setImpostors(const PackedModels& p, VkDescriptorSet frameSet, streaming::DiskTileCache* cache) {
  impostors_.reset();
  impostorCacheFigures_ = {};
  const auto layers = static_cast<uint32_t>(p.impostorModels.size());
  std::string key;
  if (cache) {
    key = impostorKey(p);
    impostors_ = loadCachedImpostors(*ctx_, *cache, key, layers, impostorCacheFigures_);
  }
  if (!impostors_) {
    captureImpostors(p.impostorModels, frameSet);
    if (cache) storeCachedImpostors(*ctx_, *cache, key, *impostors_, impostorCacheFigures_);
  }
  for (size_t s = 0; s < sets_.size(); ++s) {
    writeSlotSet(s);
    writeSampledImage(*ctx_, sets_[s], sampler_.get(), impostors_->albedo().view.get(), 8);
    writeSampledImage(*ctx_, sets_[s], sampler_.get(), impostors_->normalDepth().view.get(), 9);
  }
}

bool TreePass::setModels(std::span<const TreeModelSet> sets, uint64_t budgetBytes, VkDescriptorSet frameSet,
                         streaming::DiskTileCache* impostorCache) {
  vkDeviceWaitIdle(ctx_->device());
  models_.clear();
  modelBlock_.assign(sizeof(TreeModelGpu) * kMaxTreeModels, 0);
  pageCapacity_ = 0;
  const PackedModels p = packModels(sets);
  if (models_.empty()) return false;
  const auto count = static_cast<uint32_t>(models_.size());

  const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  vertices_ = createBufferWithData(*ctx_, p.vertices.data(), p.vertices.size() * sizeof(p.vertices[0]),
                                   VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, "tree vertices");
  indices_ = createBufferWithData(*ctx_, p.indices.data(), p.indices.size() * sizeof(uint32_t),
                                  VK_BUFFER_USAGE_INDEX_BUFFER_BIT, "tree indices");
  branches_ = createBufferWithData(*ctx_, p.branches.data(), p.branches.size() * sizeof(p.branches[0]), storage,
                                   "tree branches");
  const uint64_t fixed = vertices_.size + indices_.size + branches_.size;
  if (fixed > budgetBytes) return false;
  const VkDeviceSize visibleBytes = createDrawBuffers(count);
  if (!createInstancePool(fixed + visibleBytes, budgetBytes, count)) return false;
  setImpostors(p, frameSet, impostorCache);
  return true;
}

}  // namespace vegstream::render
