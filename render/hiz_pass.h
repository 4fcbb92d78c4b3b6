#pragma once
// Hi-Z occlusion culling of plant seed triangles: the hierarchical Z-buffer of Greene, Kass &
// Miller, "Hierarchical Z-Buffer Visibility" (SIGGRAPH 1993), built each frame from the
// terrain's depth and tested on the GPU before the classify pass expands any cluster.
//
// Frame order (render/frame_passes.cpp FramePasses::record): rendering scope 1 draws sky + terrain and
// ends; recordBuild reduces the depth attachment into a pyramid; the classify pass calls
// recordCull (its CullHook) after uploading the triangles, so triangles hidden behind canyon
// walls and ridges are never classified into plants nor drawn (and groups of a species hidden
// on their triangle — grass behind a ridge that does not hide trees — are dropped when
// classified); scope 2 draws the plants.
//
// The pyramid is a storage buffer, not a mip-mapped image: level l has ceil(W / 2^(l+1)) ×
// ceil(H / 2^(l+1)) texels (rounded UP, unlike Vulkan mips, so no edge pixel is lost), texel
// (i, j) covers exactly the pixels [i·2^(l+1), (i+1)·2^(l+1)) × [j·2^(l+1), (j+1)·2^(l+1)) on
// screen, and holds the FARTHEST depth under them — reverse-Z (1 near, 0 far), so the minimum,
// over every MSAA sample. Level 0 is half resolution; the last level is 1 × 1.
//
// The test (shaders/hiz_cull.comp) is conservative, per species: species s is hidden on a
// triangle only when the nearest depth of a box holding all its plants there (and one holding
// their planar shadows) is strictly behind the
// farthest depth of the pyramid texels covering the box's screen rectangle (at the finest level
// where they are ≤ 8 × 8: Greene's 2 × 2 is too coarse along ridge crests, where a big texel also
// holds the sky). Boxes that reach the near plane or lie wholly off screen are kept.
//
// Contract: recordBuild expects the depth attachment in DEPTH_ATTACHMENT_OPTIMAL, written by a
// rendering scope that has ended, and leaves it in DEPTH_ATTACHMENT_OPTIMAL (contents kept) for
// a second scope that loads it. One pyramid serves both frame slots (the build's first barrier
// orders it after the previous frame's tests); the visibility flags and counters are per slot.

#include <array>
#include <vector>

#include "render/context.h"
#include "render/frame_types.h"
#include "render/frame_slots.h"
#include "render/gpu_resources.h"
#include "render/handle.h"
#include "render/render_targets.h"
#include "vegetation/species_catalog.h"

namespace vegstream::render {

struct HizLevel {
  uint32_t width = 0, height = 0;  // texels
  uint32_t offset = 0;             // first texel in the pyramid buffer
};

// The levels of the pyramid of a `extent` depth target (level 0: half resolution, rounded up).
std::vector<HizLevel> hizLevels(VkExtent2D extent);

// How far (m) a plant of each species of `catalog` can reach from its root in any direction:
// height, lean and the widest thing drawn for it (the markers are 3 × the plant's width or
// 0.3 × its height); −1 for bare soil and unused slots.
std::array<float, vegetation::kMaxSpecies> speciesReach(const vegetation::SpeciesCatalog& catalog);

class HizPass {
 public:
  static constexpr int kSlots = kFramesInFlight;  // one buffer set per frame in flight

  // `frameLayout`: the renderer's frame-uniform set layout (set 0 of the cull kernel).
  // `terrainDepth`: the terrain was rasterised in compute (render/terrain_raster_pass.h): the
  // pyramid is built from that buffer of depth samples, not from the depth attachment.
  HizPass(const Context& ctx, VkDescriptorSetLayout frameLayout, const RenderTargets& targets,
          VkBuffer terrainDepth = VK_NULL_HANDLE);

  // The species the bounds are made for (speciesReach); call it with the classify pass's
  // setCatalog (the test's bit s is species s of this catalog).
  void setCatalog(const vegetation::SpeciesCatalog& catalog);

  // Outside rendering, after the terrain's scope ended (or its compute raster): depth → pyramid.
  void recordBuild(VkCommandBuffer cmd);

  // The occlusion test of `count` triangles into `visible` (classify's CullHook), after
  // recordBuild in the same command buffer; counts land in slot `slot`'s figures. Where the
  // species in `drawn` (bits) may show, it marks the screen for the terrain's depth
  // (render/terrain_depth_handover.h).
  void recordCull(VkCommandBuffer cmd, int slot, VkDescriptorSet frameSet, VkBuffer triangles, VkBuffer visible,
                  uint32_t count, uint32_t clusterSize, bool shadows, uint32_t drawn);

  // Slot `slot`'s counts of its last culled frame, into `f` (after its fence).
  void readFigures(int slot, VegetationFigures& f) const;

  VkBuffer pyramid() const { return pyramid_.get(); }
  const std::vector<HizLevel>& levels() const { return levels_; }
  uint64_t gpuBytes() const;

 private:
  // The constructor's steps: the depth, reduce and cull pipelines; the depth and reduce sets and
  // each slot's counters and cull set.
  void createPipelines(VkDescriptorSetLayout frameLayout, const RenderTargets& targets);
  void createSets(VkBuffer terrainDepth, const RenderTargets& targets);
  struct Slot {
    GpuBuffer counters;  // host-readable: tested, culled, clusters culled, plants culled
    VkDescriptorSet cullSet = VK_NULL_HANDLE;
    VkBuffer boundTriangles = VK_NULL_HANDLE, boundVisible = VK_NULL_HANDLE;
  };

  const Context* ctx_;
  const RenderTargets* targets_;
  std::vector<HizLevel> levels_;
  bool fromBuffer_ = false;  // level 0 from the compute raster's depth samples, not the attachment
  std::array<float, vegetation::kMaxSpecies> reach_{};
  uint32_t speciesCount_ = 0;
  GpuBuffer pyramid_;
  DescriptorSetLayout depthLayout_, reduceLayout_, cullLayout_;
  DescriptorPool pool_;
  VkDescriptorSet depthSet_ = VK_NULL_HANDLE, reduceSet_ = VK_NULL_HANDLE;
  PipelineLayout depthPipelineLayout_, reducePipelineLayout_, cullPipelineLayout_;
  Pipeline depth_, reduce_, cull_;
  std::array<Slot, kSlots> slots_;
};

}  // namespace vegstream::render
