#pragma once
// The terrain rasterised and shaded in compute (`--terrain-shading compute`): no graphics work
// at all for the terrain. Four dispatches (shaders/terrain_bin.comp, terrain_bin_scan.comp,
// terrain_raster*.comp):
// 1. setup: each triangle of the frame's index buffer to clip space, culled as the hardware
//    pipeline culls (frustum, back faces), clipped by the near plane, snapped to 1/256 pixel,
//    and counted into every 8 × 8-pixel tile it may touch;
// 2. scan: each tile's start in one list array;
// 3. fill: each tile's list of the triangles that may touch it;
// 4. raster + shade: a workgroup per tile keeps, per sample, the nearest triangle (a watertight
//    edge-function test: shared edges are evaluated from one canonical end, ties by a fill rule),
//    writes the depth per sample into a buffer and shades the pixel with the deferred shade's own
//    code (terrain_shade.glsl), sky included, into the colour target's storage view.
//
// Why: on NVIDIA's H100/H200 the graphics units are 2 of 66 TPCs, and the hardware raster of the
// terrain's ~90 k triangles at 4× MSAA took 1.9 ms of which a depth-only raster alone was 1.4 ms
// (render/README.md) — more than issue 17's whole terrain budget of 1.0 ms — while compute runs
// on all 132 SMs.
//
// The rest of the frame sees the terrain as if drawn with graphics: TerrainDepthHandover
// (render/terrain_depth_handover.h) writes the depth samples into the depth attachment where the
// trees and plants may be drawn, so they are depth-tested against it by the hardware, hidden
// fragments rejected before they are shaded: one depth per pixel, and each sample's own over the
// 8 × 8 tiles where a pixel's samples differ by more than 5 % of the distance (terrain edges:
// the raster flags them per tile). (The first version cleared the attachment, and every fragment
// tested itself against the samples in its shader: the trees pass then cost 1.23 / 3.11 ms p50 /
// p99 on benchmark-30s against 0.82 / 2.53 with the depth handed over, measured side by side.)
// The Hi-Z build reads the same buffer (HizPass, built with it).
//
// Contract: the device can store into colour targets of the frame's sample count (as the deferred
// shade); record() runs outside rendering, after TerrainPass::prepare of the same slot. The tile
// lists grow when a frame needed more than they hold (that frame drops the excess: figures()).

#include <array>
#include <cstdint>
#include <functional>

#include "render/gpu_resources.h"
#include "render/handle.h"
#include "render/render_targets.h"
#include "render/terrain_pass.h"
#include "render/terrain_shade_pass.h"

namespace vegstream::render {


// What one frame's raster did (read after its fence).
struct TerrainRasterFigures {
  uint32_t rasterTriangles = 0;  // after culling and near clipping (a clipped triangle may be two)
  uint32_t tileEntries = 0;      // triangle-in-tile entries the lists needed
  uint32_t tileEntriesDropped = 0;
};

class TerrainRasterPass {
 public:
  static constexpr int kSlots = TerrainPass::kSlots;
  static constexpr uint32_t kTile = 8;   // pixels per tile side (terrain_raster.glsl)

  // `tileEdges`: TerrainDepthHandover::tileEdges(), the per-tile edge flags the raster writes.
  TerrainRasterPass(const Context& ctx, VkDescriptorSetLayout frameLayout, const TerrainPass& terrain,
                    const RenderTargets& targets, VkBuffer tileEdges);

  // The terrain's depth per pixel and sample ((y · width + x) · samples + s; reverse-Z, 0: sky),
  // written by record(); readable by fragment and compute stages afterwards.
  VkBuffer depthBuffer() const { return depth_.get(); }

  using RetireBuffer = std::function<void(GpuBuffer&&)>;
  // `triangles`: what prepare() returned for the slot. Timed as two passes by the caller's hooks:
  // `binned` is called between the binning (setup, scan, fill) and the raster + shade.
  void record(VkCommandBuffer cmd, int slot, VkDescriptorSet frameSet, const TerrainPass& terrain,
              const RenderTargets& targets, uint64_t triangles, const RetireBuffer& retire,
              const std::function<void()>& binned);
  // After the frame's last reader of the depth samples (its last rendering scope): the next
  // frame's raster waits for them here, not at its start, where the wait would also hold it
  // behind the graphics work recorded before it.
  void recordEndOfFrame(VkCommandBuffer cmd) const;
  TerrainRasterFigures figures(int slot) const;

  uint64_t gpuBytes() const;

 private:
  void ensureCapacity(GpuBuffer& buffer, VkDeviceSize bytes, const char* what, const RetireBuffer& retire);
  // record()'s steps: the tile lists and triangle buffer grown for `triangles`; slot s's inputs
  // set written; the bin, scan and bin-again dispatches that sort the triangles into tiles.
  void growLists(int slot, uint64_t triangles, const RetireBuffer& retire);
  // The constructor's pipelines: bin, scan and raster (compute).
  void createPipelines(VkDescriptorSetLayout frameLayout, const TerrainPass& terrain, const RenderTargets& targets);
  void writeInputs(size_t s, const TerrainGeometry& g, const RenderTargets& targets);
  void recordBinning(VkCommandBuffer cmd, TerrainComputePush& push, uint64_t triangles);
  // After the previous frame's readers: the tile counts and the counters at zero.
  void resetCounts(VkCommandBuffer cmd) const;

  const Context* ctx_;
  uint32_t tilesX_ = 0, tilesY_ = 0, samples_ = 1;
  uint32_t listCapacity_ = 0;  // tile list entries
  DescriptorSetLayout inputsLayout_;
  DescriptorPool pool_;
  std::array<VkDescriptorSet, kSlots> inputs_{};
  std::array<GpuBuffer, kSlots> readback_;  // host-readable copies of counters_: TerrainRasterFigures
  GpuBuffer counters_, triangles_, tileCounts_, tileStarts_, tileLists_, depth_;
  VkBuffer tileEdges_;  // the per-tile edge flags (terrain_raster.glsl), TerrainDepthHandover's
  PipelineLayout layout_;
  Pipeline bin_, scan_, raster_;
};

}  // namespace vegstream::render
