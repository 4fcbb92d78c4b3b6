#pragma once
// The terrain rasterised in compute (render/terrain_raster_pass.h) hands its depth samples to the
// depth attachment, so that the trees and plants drawn after it are depth-tested against it by the
// hardware — but only where a plant or a tree may be drawn.
//
// Why: writing the multisampled depth attachment is a full-screen write through the few graphics
// units of an H100/H200 whatever writes it: a full-screen draw of every pixel cost 0.63 ms at
// 1080p × 4 and a clear alone 0.60 (benchmark-30s, an H100, bench/README.md), and a draw over a
// half or a quarter of the screen cost half or a quarter of that. Most of the screen holds no
// vegetation in many views (rock, far terrain, sky): there nothing is depth-tested, and the
// attachment may hold anything. So it is neither cleared nor written there.
//
// How: at the frame's start every cell of common/depth_tile_marks.glsl is unmarked. The passes that
// decide what is drawn mark where it may fall: the tree classify every tree it appends (a sphere
// around the model), the Hi-Z cull every seed triangle whose plants may show (the boxes it tests:
// the plants, their planar shadows). Then, after those passes and the raster, one thread per row of
// 8 × 8 tiles (shaders/terrain_depth_tiles.comp) lists the wanted tiles: those with a depth edge
// (the raster's flags) to be written per sample (terrain_depth_edge.vert, terrain_depth.frag), the
// others as runs along the row, a quad per run written per pixel (terrain_depth_span.vert,
// terrain_depth_pixel.frag) — or, where the wanted tiles are 85 % of the screen or more, one
// full-screen triangle per pixel, which costs less than the runs of it. Every tile is wanted where nothing marks the plants (no occlusion
// culling, markers) or when the frame's depth is read back.
//
// Contract: recordBeginFrame before the tree classify; record after the raster, the Hi-Z cull
// and the blade expansion, before the trees' and the plants' scopes. marks() is the frame set's
// binding 10; tileEdges() the raster's per-tile edge flags.

#include <array>
#include <cstdint>

#include "render/frame_types.h"
#include "render/gpu_resources.h"
#include "render/handle.h"
#include "render/render_targets.h"
#include "render/terrain_pass.h"

namespace vegstream::render {

// What one frame's hand-over wrote (read after its fence).
struct DepthHandoverFigures {
  uint32_t pixelTiles = 0;  // 8 × 8 tiles written per pixel
  uint32_t edgeTiles = 0;   // 8 × 8 tiles written per sample
};

class TerrainDepthHandover {
 public:
  static constexpr int kSlots = TerrainPass::kSlots;

  TerrainDepthHandover(const Context& ctx, VkDescriptorSetLayout frameLayout, const RenderTargets& targets,
                       DepthTiles mode);

  DepthTiles mode() const { return mode_; }
  VkBuffer marks() const { return marks_.get(); }
  VkBuffer tileEdges() const { return tileEdges_.get(); }

  void recordBeginFrame(VkCommandBuffer cmd) const;
  // `everything`: every tile wanted, whatever the marks.
  void record(VkCommandBuffer cmd, VkDescriptorSet frameSet, const RenderTargets& targets, bool everything) const;
  // At the frame's end (after record): the counts into slot `slot`'s figures, off the frame's
  // critical path.
  void recordFigures(VkCommandBuffer cmd, int slot) const;
  DepthHandoverFigures figures(int slot) const;
  uint64_t gpuBytes() const;

 private:
  void createPipelines(VkDescriptorSetLayout frameLayout, const RenderTargets& targets);
  void recordList(VkCommandBuffer cmd, VkDescriptorSet frameSet, bool everything) const;

  const Context* ctx_;
  DepthTiles mode_;
  uint32_t tilesX_ = 0, tilesY_ = 0, samples_ = 1;
  GpuBuffer marks_, tileEdges_, spans_, edges_;
  std::array<GpuBuffer, kSlots> readback_;  // runs, tiles in runs, edge tiles
  DescriptorSetLayout listLayout_, drawLayout_;
  DescriptorPool pool_;
  VkDescriptorSet listSet_ = VK_NULL_HANDLE, spanSet_ = VK_NULL_HANDLE, edgeSet_ = VK_NULL_HANDLE;
  PipelineLayout listPipelineLayout_, drawPipelineLayout_;
  Pipeline list_, span_, full_, edge_;
};

}  // namespace vegstream::render
