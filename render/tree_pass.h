#pragma once
// Trees on the GPU (issue 20): the models (every species' variants, both mesh levels, one vertex,
// index and branch buffer), the instance pool in pages (render/tree_layout.h), the octahedral
// impostor atlas (render/tree_impostors.h), and per frame the classify dispatch
// (shaders/tree_classify.comp: cull, level of detail, cross-fade, appends to indirect draws) and
// the draws: per model one indexed indirect draw per mesh level and one impostor draw.
//
// Memory is fixed when the models are set: the pool holds as many pages as the tree budget leaves
// after the models, the atlas and the visible lists; the scene gives tiles pages while there are
// any (scene/tree_field.h), and far tiles without pages are simply not drawn (the terrain's own
// colour shows there).

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include <glm/mat4x4.hpp>

#include "render/context.h"
#include "render/gpu_resources.h"
#include "render/handle.h"
#include "render/impostor_atlas_cache.h"
#include "render/tree_layout.h"

namespace vegstream::render {

class TreeImpostors;
struct TreeImpostorModel;

class TreePass {
 public:
  static constexpr int kSlots = 3;

  // `shadowTargetLayout`: render/sun_shadow_pass.h's targetLayout() (recordShadow's target);
  // `shadowGroups`, `shadowLayers`: RendererOptions::treeShadowGroups and treeShadowLayers (0:
  // the device's groups, the layers each cascade's texel asks for).
  TreePass(const Context& ctx, VkDescriptorSetLayout frameLayout, VkSampleCountFlagBits samples,
           VkDescriptorSetLayout shadowTargetLayout, uint32_t shadowGroups = 0, uint32_t shadowLayers = 0);
  ~TreePass();

  // Uploads the models, captures their impostors and sizes the pool from `budgetBytes` (the
  // models, atlas and lists first; what is left is pages). Waits for the GPU. Returns false when
  // the budget does not even hold the models (then no trees are drawn). `frameSet`: any frame
  // slot's set 0 (the capture's shaders declare it). `impostorCache` (may be null): where the
  // impostors are looked up first and stored after a capture (impostor_atlas_cache.h).
  bool setModels(std::span<const TreeModelSet> sets, uint64_t budgetBytes, VkDescriptorSet frameSet,
                 streaming::DiskTileCache* impostorCache = nullptr);
  // What the last setModels did with the impostor cache.
  const ImpostorCacheFigures& impostorCacheFigures() const { return impostorCacheFigures_; }
  uint32_t pageCapacity() const { return pageCapacity_; }
  uint32_t modelCount() const { return static_cast<uint32_t>(models_.size()); }
  uint64_t gpuBytes() const;

  using RetireBuffer = std::function<void(GpuBuffer&&)>;
  // Outside rendering: page uploads, then the classify dispatch (needs set 0's simulation block).
  // `shadowMarginM`: trees this far outside the view still classify (they cast into it; 0 without
  // shadows).
  // `lodScale`: treeLodScale of the view.
  void recordClassify(VkCommandBuffer cmd, int slot, VkDescriptorSet frameSet, const TreeRequest& request,
                      const glm::dmat4& viewProj, float lodScale, float shadowMarginM, const RetireBuffer& retire);
  // Inside rendering (colour target of `samples`), after recordClassify.
  void recordDraw(VkCommandBuffer cmd, int slot, VkDescriptorSet frameSet);
  // Outside rendering, into layer `cascade` of the sun's shadow map (`target`: render/sun_shadow_pass.h,
  // cleared and writable by compute): the classified trees whose sphere reaches `cascade`'s box —
  // impostor, reduced or full in the view — as their impostor turned to the sun, through the
  // cascade's matrix, rasterised in compute (shaders/tree_shadow_raster.comp; the models' cards
  // cost 15 × the impostors there).
  // `texelM`: the cascade's texel (m), which sizes the dispatch (unless the constructor fixed its
  // layers).
  void recordShadow(VkCommandBuffer cmd, int slot, VkDescriptorSet frameSet, int cascade, const glm::mat4& matrix,
                    float texelM, VkDescriptorSet target);
  // The figures of the frame last recorded in `slot`, once its fence has signalled.
  TreeFigures figures(int slot) const;

  // The instances model `model`'s list at mesh level `lod` (0 full, 1 reduced) held after the last
  // frame's classify and sort, in draw order (tests). Waits for the GPU.
  std::vector<uint32_t> readList(uint32_t model, uint32_t lod) const;

  // The impostor atlas (tests): layer per model, RGBA8 albedo + coverage.
  const TreeImpostors* impostors() const { return impostors_.get(); }

 private:
  // Per level of detail: bark and cards [firstIndex, + indexCount), then the crown's core
  // (vegetation::TreeMesh::coreFirstIndex) [firstIndex + indexCount, + coreCount).
  struct ModelDraw {
    uint32_t firstIndex[2], indexCount[2], vertexOffset[2], coreCount[2];
  };
  void createPipelines(VkDescriptorSetLayout frameLayout, VkDescriptorSetLayout shadowTargetLayout);
  // recordClassify()'s steps: the request's pages copied into the pool through slot s's staging
  // buffer; slot s's TreeBlock written for the view.
  void recordPageUploads(VkCommandBuffer cmd, size_t s, const TreeRequest& request, const RetireBuffer& retire);
  void writeBlock(size_t s, const TreeRequest& request, const glm::dmat4& viewProj, float lodScale, float shadowMarginM,
                  uint32_t pages);
  // setModels's steps (render/tree_models.cpp): the models packed into one mesh with their GPU
  // records and impostor spheres; the visible lists and draws of `count` models (returns the
  // lists' bytes); the per-slot buffers and the instance pool from what the budget leaves after
  // `fixedBytes` (false: not one page); slot `s`'s set; the impostors captured, then every set.
  struct PackedModels;
  PackedModels packModels(std::span<const TreeModelSet> sets);
  VkDeviceSize createDrawBuffers(uint32_t count);
  bool createInstancePool(uint64_t fixedBytes, uint64_t budgetBytes, uint32_t count);
  void writeSlotSet(size_t s);
  // The first entry of model m's visible list at level lod (shaders/common/tree_layout.glsl
  // treeRegionBase).
  uint32_t regionBase(uint32_t m, uint32_t lod) const;
  void captureImpostors(std::span<const TreeImpostorModel> impostorModels, VkDescriptorSet frameSet);
  // The SHA-256 of what the capture reads (impostor_atlas_file.h).
  std::string impostorKey(const PackedModels& p) const;
  void setImpostors(const PackedModels& p, VkDescriptorSet frameSet, streaming::DiskTileCache* cache);

  const Context* ctx_;
  VkSampleCountFlagBits samples_;
  uint32_t shadowLayers_;  // 0: from the cascade's texel
  uint32_t shadowGroups_;  // workgroups of a cascade's dispatch, all layers together
  DescriptorSetLayout setLayout_;
  DescriptorPool pool_;
  std::array<VkDescriptorSet, kSlots> sets_{};
  PipelineLayout classifyLayout_, drawLayout_, shadowLayout_;
  Pipeline classifyPipeline_, sortPipeline_, meshPipeline_, corePipeline_, impostorPipeline_, shadowPipeline_;
  Sampler sampler_;

  std::vector<ModelDraw> models_;
  GpuBuffer vertices_, indices_, branches_;
  GpuBuffer instances_, visible_, meshDraws_, impostorDraws_, drawTemplate_, counters_;
  std::array<GpuBuffer, kSlots> uniforms_, pageCounts_, staging_, readback_;
  std::unique_ptr<TreeImpostors> impostors_;
  ImpostorCacheFigures impostorCacheFigures_;
  std::vector<uint8_t> modelBlock_;  // the models' part of the TreeBlock, packed once
  uint32_t pageCapacity_ = 0;
  std::array<uint32_t, 3> capacity_{};                          // visible entries per model and level
  std::array<uint32_t, kTreeShadowCascades> casterCapacity_{};  // shadow casters per model and cascade
  std::array<uint32_t, kSlots> slotPages_{};
  std::array<bool, kSlots> slotRecorded_{};
  std::array<bool, kSlots> slotCores_{};  // the request's cores: drawn or not
};

}  // namespace vegstream::render
