#pragma once
// The classify pass (core seed ../shared/seeds/001_3eca9f2c7752e4fb.txt §3.5, two-stage
// per-species rendering, in Vulkan terms): each frame's seed triangles are binned by cluster
// count (§3.2 eq. 15, vegetation/plant_bins.h), one compute dispatch per bin expands them into
// clusters, samples the imagery under each cluster, picks the species and appends the group to
// its species' buffer with atomics (shaders/classify.comp); a last dispatch turns the counters
// into one indirect draw per species (shaders/classify_finish.comp). The species pipelines draw
// from `records()` with `indirect()`; vegetation/plant_seeding.h is the CPU reference.
//
// Buffers per frame slot: triangles and bin order (host-upload, grown as needed), counters and
// records (device-local; `clustersPerSpecies` groups per species — more are counted, not
// drawn), indirect draws, and a read-back copy of the counters for the figures.

#include <array>
#include <functional>
#include <span>

#include "render/classify_layout.h"
#include "render/context.h"
#include "render/frame_slots.h"
#include "render/frame_types.h"
#include "render/gpu_resources.h"
#include "render/growing_buffer.h"
#include "render/handle.h"

namespace vegstream::vegetation {
struct BinnedTriangles;
}  // namespace vegstream::vegetation

namespace vegstream::render {

struct ClassifyOptions {
  uint32_t clustersPerSpecies = 1u << 16;
  // Makes the per-frame triangle, order and visibility buffers' next sizes ahead of need
  // (growing_buffer.h); null: the frame that outgrows one makes it.
  TaskRunner* tasks = nullptr;
};

class ClassifyPass {
 public:
  static constexpr int kSlots = kFramesInFlight;  // one buffer set per frame in flight
  using RetireBuffer = std::function<void(GpuBuffer&&)>;
  // Records the occlusion test of the frame's `count` seed triangles (the slot's `triangles`
  // buffer, uploaded): writes visible[t] (uint; 0: hidden) into `visible` with compute shaders
  // (render/hiz_pass.h). The classify dispatches then skip hidden triangles.
  using CullHook = std::function<void(VkCommandBuffer cmd, VkBuffer triangles, VkBuffer visible, uint32_t count)>;

  ClassifyPass(const Context& ctx, const ClassifyOptions& options);

  // The species every later frame classifies into (uploaded now; waits for nothing: call it
  // before the first frame or when no frame is in flight).
  void setCatalog(const vegetation::SpeciesCatalog& catalog);
  // false: every group is drawn at full size or not at all — the fades by size (sequence end,
  // species horizon, imagery cross-fade) off, for comparing what they hide (`--plant-fades off`).
  void setFades(bool on) { fades_ = on; }

  // Outside rendering: uploads `triangles`, bins them and records the dispatches for slot
  // `slot`. `imagery` is the imagery array the triangles' layers index, viewed as UNORM (the
  // sRGB bytes; shader-readable); `companions` its NDVI + landcover
  // array (TerrainPass::companionView), read as `companionFlags` says (ImageryCompanions::flags).
  // The indirect draws get one vertex per group (a patch) for the species in `patchMask` (bit s:
  // species s is drawn by a plant pipeline), `verticesPerGroup` for the others (markers).
  // With `cull`, the triangles it marks hidden are not expanded (no cluster, no group, no draw).
  // With `canopy` (the crowns near the camera the triangles are relative to), groups under a
  // crown thin out (vegetation/canopy_cells.h).
  // Returns the CPU-side figures (the GPU's counts come from readFigures after the fence).
  VegetationFigures record(VkCommandBuffer cmd, int slot, std::span<const SeedTriangleGpu> triangles,
                           uint32_t clusterSize, VkImageView imagery, VkImageView companions, uint32_t companionFlags,
                           uint32_t verticesPerGroup, uint32_t patchMask, const RetireBuffer& retire,
                           const CullHook& cull = {}, const vegetation::CanopyTable* canopy = nullptr);

  // The GPU's counts of slot `slot`'s last frame, merged into `f` (after its fence).
  void readFigures(int slot, VegetationFigures& f) const;
  // The overflow thinning's pressure for the frames recorded from now on, from the groups a
  // read-back frame wanted (vegetation/overflow_thinning.h); thinning() is the current one.
  void updateThinning(const VegetationFigures& f);
  // The same from the counts in slot `slot`'s figures (its frame done); −1: no pressure.
  void updateThinningFromSlot(int slot);
  void setThinning(const std::array<float, kSpeciesSlots>& pressure) { thinning_ = pressure; }
  const std::array<float, kSpeciesSlots>& thinning() const { return thinning_; }

  VkBuffer records(int slot) const { return slots_[size_t(slot)].records.get(); }
  VkBuffer triangles(int slot) const { return slots_[size_t(slot)].triangles.get(); }
  VkBuffer indirect(int slot) const { return slots_[size_t(slot)].indirect.get(); }
  VkBuffer species() const { return species_.get(); }
  uint32_t clustersPerSpecies() const { return options_.clustersPerSpecies; }
  uint32_t speciesCount() const { return speciesCount_; }
  // The renderer kind of species s (vegetation::RendererKind), kNoKind for bare soil / none.
  static constexpr uint32_t kNoKind = 0xffffffffu;
  uint32_t kind(uint32_t s) const { return kinds_[s]; }
  uint64_t gpuBytes() const;

 private:
  struct Slot {
    GrowingBuffer triangles, order;
    GpuBuffer counters, records, indirect, figures;
    GrowingBuffer visible;  // per triangle, written by the cull hook
    GpuBuffer canopy;   // vegetation::CanopyHeader and kCanopyCells² entries (host-upload)
    VkDescriptorSet classifySet = VK_NULL_HANDLE, finishSet = VK_NULL_HANDLE;
    VkImageView boundImagery = VK_NULL_HANDLE, boundCompanions = VK_NULL_HANDLE;
  };
  void ensureCapacity(Slot& s, size_t triangles, size_t orderEntries, const RetireBuffer& retire);
  void writeSets(Slot& s, VkImageView imagery, VkImageView companions);
  // Slot i's buffers and sets (the constructor's).
  void createSlot(size_t i);
  // record()'s dispatches: the classify over every non-empty bin (returns how many), then the
  // finish that turns the counters into draws.
  uint32_t dispatchClassify(VkCommandBuffer cmd, const Slot& s, const vegetation::BinnedTriangles& bins,
                            uint32_t clusterSize, uint32_t companionFlags, bool culled);
  void dispatchFinish(VkCommandBuffer cmd, const Slot& s, uint32_t verticesPerGroup, uint32_t patchMask);

  const Context* ctx_;
  ClassifyOptions options_;
  uint32_t speciesCount_ = 0;
  std::array<uint32_t, kSpeciesSlots> kinds_{};
  GpuBuffer species_;
  Sampler sampler_;
  DescriptorSetLayout classifyLayout_, finishLayout_;
  DescriptorPool pool_;
  PipelineLayout classifyPipelineLayout_, finishPipelineLayout_;
  Pipeline classify_, finish_;
  std::array<Slot, kSlots> slots_;
  bool fades_ = true;
  std::array<float, kSpeciesSlots> thinning_{};
};

}  // namespace vegstream::render
