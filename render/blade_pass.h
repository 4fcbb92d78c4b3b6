#pragma once
// The compute blade path (core seed ../shared/seeds/001_3eca9f2c7752e4fb.txt §2.3–2.4, §3.5–3.6;
// issue 17): the plant kinds of the species pipelines — grass, gravel and flowers — expanded into
// triangles by a compute pass, then drawn by one trivial vertex stage and the species pipelines'
// own fragment stage (shaders/plant.frag: the same eq. 13–14 shading, computed alpha-to-coverage
// and black screen-door shadows).
//
// Why: the tessellation path (plant_pass.h) recomputes a plant's parameters for every vertex in
// the evaluation stage and extrudes it in a geometry stage; on GPUs whose graphics stages run on
// a few units (the H200: 2 graphics TPCs, compute on all 132 SMs) that per-vertex work is the
// bottleneck. Here each plant's values (root, orientation, height, width, stiffness, colour
// inputs, eq. 4 segment count, the group's frustum test) are computed once, by compute
// (shaders/blades.comp), and the graphics stages only fetch and project.
//
// Contract: recordExpand, outside rendering and after ClassifyPass::record of the same slot,
// writes for every plant the tessellation path would draw exactly the triangles its geometry
// stages would emit (same plants, blades, segment counts, shadows; vertex positions equal up to
// float rounding), plus an indexed indirect draw whose count the GPU wrote (reservation by
// atomics); recordDraw, inside the frame's rendering scope, draws it. The buffers grow (per slot,
// retired through the deletion queue) to the CPU's upper bound of the frame's vertices, indices
// and plants (per seed triangle: its most plants × the largest plant at the triangle's most
// eq. 4 segments), up to a ceiling (RendererOptions::bladeMaxVertices); a plant beyond the
// ceiling is dropped whole and counted (VegetationFigures::bladesDropped), the indices it had
// reserved below the ceiling made degenerate: never a write out of bounds, never a stray triangle.

#include <array>

#include "render/classify_pass.h"
#include "render/context.h"
#include "render/frame_types.h"
#include "render/gpu_resources.h"
#include "render/growing_buffer.h"
#include "render/handle.h"
#include "render/plant_pass.h"

namespace vegstream::render {

// What the blade vertex and index buffers start at. Small: grown as the plants come in (a CPU
// rasteriser: memory is the host's). On a GPU each new 64–256 MiB buffer stalled the frame
// thread for 2–7 ms where it was made and first used (the driver maps it: H200, benchmark-30s,
// one frame per slot as the plants came in at t = 8.7 s, and again at 9.0 s for the indices):
// Half starts them at half their ceiling, one growth left per slot; Full makes them at the
// ceiling and uses them once before the first frame, when every slot's ceilings together take
// at most a sixteenth of the device's memory (the H200: 1.1 GB of 141; benchmark-30s grows them
// to the ceiling anyway).
enum class BladeBufferStart { Small, Half, Full };
BladeBufferStart chooseBladeBufferStart(bool software, uint64_t deviceLocalBytes, uint64_t allSlotsCeilingBytes);

class BladePass {
 public:
  using RetireBuffer = ClassifyPass::RetireBuffer;

  // `maxVertices`: the ceiling of one frame slot's vertex buffer (RendererOptions::bladeMaxVertices);
  // indices and the plant count (numbered, not stored) follow from it. `tasks` (may be null)
  // makes the vertex and index buffers' next sizes ahead of need (growing_buffer.h).
  // The vertex and index buffers start as chooseBladeBufferStart says for the device.
  BladePass(const Context& ctx, VkDescriptorSetLayout frameLayout, VkSampleCountFlagBits samples, uint32_t maxVertices,
            TaskRunner* tasks = nullptr);

  // The catalog the classify pass sorts into (its tallest plant bounds the segment counts the
  // buffers are sized for); call with ClassifyPass::setCatalog.
  void setCatalog(const vegetation::SpeciesCatalog& catalog);

  // Species with a blade kind (the plant pipelines' kinds): bit s set.
  static uint32_t bladeMask(const ClassifyPass& classify) { return PlantPass::patchMask(classify); }

  // Outside rendering: expands slot `slot`'s classified plants of the species in bladeMask.
  // `triangles` and `clusterSize` are what the classify pass was given (the plant bound);
  // `imagery` is the imagery array's sRGB view (the ground colour under each plant).
  void recordExpand(VkCommandBuffer cmd, int slot, VkDescriptorSet frameSet, const ClassifyPass& classify,
                    const PlantPass& plants, std::span<const SeedTriangleGpu> triangles, uint32_t clusterSize,
                    VkImageView imagery, const PlantDrawOptions& options, const RetireBuffer& retire);

  // Inside rendering: the slot's expanded triangles (nothing when recordExpand drew nothing).
  void recordDraw(VkCommandBuffer cmd, int slot, VkDescriptorSet frameSet) const;

  // After the slot's fence: what the expansion wrote (when this frame expanded).
  void readFigures(int slot, VegetationFigures& f) const;

  // Whether the slot's last frame expanded (its counters are meaningful).
  bool expanded(int slot) const { return slots_[size_t(slot)].expanded; }

  uint64_t gpuBytes() const;
  // The slot's vertex buffer and how many vertices its last expansion wrote (after its fence).
  VkBuffer vertexBuffer(int slot) const { return slots_[size_t(slot)].vertices.get(); }
  uint64_t writtenVertices(int slot) const;

 private:
  // The constructor's steps: the set layouts, pool and pipelines; each slot's sets and buffers,
  // started as chooseBladeBufferStart says.
  void createPipelines(VkDescriptorSetLayout frameLayout, VkSampleCountFlagBits samples);
  void createSlots(TaskRunner* tasks);
  struct Slot {
    GrowingBuffer vertices, indices;
    GpuBuffer state, figures;
    VkDescriptorSet inputSet = VK_NULL_HANDLE, bladeSet = VK_NULL_HANDLE;
    uint32_t vertexCapacity = 0, indexCapacity = 0, plantCapacity = 0;
    PlantPush drawPush{};
    bool expanded = false;
  };
  // recordExpand()'s sets: slot s's inputs (classify's buffers, the shape table, the imagery)
  // and its blade buffers.
  void writeSets(Slot& s, int slot, const ClassifyPass& classify, const PlantPass& plants, VkImageView imagery);
  struct Bound {
    uint64_t plants = 0, vertices = 0, indices = 0;
  };
  Bound bound(std::span<const SeedTriangleGpu> triangles, uint32_t clusterSize, const PlantDrawOptions& o) const;
  void ensureCapacity(Slot& s, const Bound& need, const RetireBuffer& retire);

  const Context* ctx_;
  uint64_t maxVertices_, maxIndices_, maxPlants_;  // one slot's ceilings
  float maxHeightM_ = 0.0f;                        // the catalog's tallest plant
  DescriptorSetLayout inputLayout_, bladeLayout_;
  DescriptorPool pool_;
  PipelineLayout layout_;
  Pipeline expand_, args_, draw_;
  std::array<Slot, ClassifyPass::kSlots> slots_;
};

}  // namespace vegstream::render
