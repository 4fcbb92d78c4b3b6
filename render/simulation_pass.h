#pragma once
// The shared simulation on the GPU (issue 19; simulation/simulation.h decides what a frame does):
// the wind grid's virtual blades (shaders/wind_sim.comp), the interaction field
// (shaders/interaction.comp) and the trail store, plus the simulation block every plant pipeline
// reads through the frame set (set 0: binding 1 the block, 2 the wind cells' moments, 3 the
// interaction field; shaders/common/simulation_fields.glsl).
//
// Memory does not grow with the plants drawn: the virtual blades (1.25 MiB), the wind cells
// (0.75 MiB), the field (16 MiB) and the store (the trail budget) are all there is; no plant has
// state. The state buffers are single (not per frame slot): the frame's barriers order a step's
// writes after the previous frames' reads on the one queue.
//
// Contract: record() runs outside rendering, before any pass that draws plants, in every frame that
// has a GpuStep; writeBlock() fills the slot's block before the frame is submitted (zeros —
// nothing moves — when the frame has no step).

#include <array>
#include <cstdint>

#include "render/context.h"
#include "render/frame_slots.h"
#include "render/gpu_resources.h"
#include "render/handle.h"
#include "simulation/simulation.h"

namespace vegstream::render {

class SimulationPass {
 public:
  // `storeBytes`: the trail store (simulation::SimulationOptions::trailBudgetMb), at least one tile.
  SimulationPass(const Context& ctx, VkDescriptorSetLayout frameLayout, uint64_t storeBytes);

  // The frame set's bindings 1–3 for slot `slot` (call once per slot at start-up).
  void writeFrameSet(VkDescriptorSet frameSet, int slot) const;
  // The slot's simulation block := `step`'s (or zeros).
  void writeBlock(int slot, const simulation::GpuStep* step);
  // The step's transfers and dispatches; their writes visible to every later shader read.
  void record(VkCommandBuffer cmd, VkDescriptorSet frameSet, const simulation::GpuStep& step);

  uint64_t gpuBytes() const;
  // Device-local buffers the tests read back (copied by the caller after the frame).
  VkBuffer windCells() const { return cells_.get(); }
  VkBuffer field() const { return field_.get(); }
  VkBuffer store() const { return store_.get(); }
  static constexpr VkDeviceSize kWindCellsBytes =
      VkDeviceSize{sizeof(simulation::shader::WindCellGpu)} * simulation::shader::kWindGrid * simulation::shader::kWindGrid;
  static constexpr VkDeviceSize kFieldBytes =
      VkDeviceSize{16} * simulation::shader::kFieldSize * simulation::shader::kFieldSize;
  static constexpr VkDeviceSize kTileBytes =
      VkDeviceSize{16} * simulation::shader::kFieldTileTexels * simulation::shader::kFieldTileTexels;

 private:
  const Context* ctx_;
  GpuBuffer blades_, cells_, field_, store_;
  std::array<GpuBuffer, kFramesInFlight> blocks_;
  DescriptorSetLayout layout_;
  DescriptorPool pool_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  PipelineLayout pipelineLayout_;
  Pipeline wind_, interaction_;
  bool cleared_ = false;  // the state buffers start as zeros (recorded with the first step and each restart)
};

}  // namespace vegstream::render
