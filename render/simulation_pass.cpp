// The shared simulation on the GPU (simulation_pass.h).
#include "render/simulation_pass.h"

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include "render/descriptors.h"
#include "render/pipeline_builder.h"
#include "shaders/interaction.comp.h"
#include "shaders/wind_sim.comp.h"

namespace vegstream::render {
namespace {

namespace sh = simulation::shader;
static_assert(sizeof(sh::SimulationParams) ==
              16 * (8 + 2 * sh::kMaxWindSources + 3 * sh::kMaxColliders + 256));  // std140: vec4s only
static_assert(sizeof(sh::VirtualBladeGpu) == 80 && sizeof(sh::WindCellGpu) == 48);

constexpr VkBufferUsageFlags kStateUse =
    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
constexpr VkPipelineStageFlags2 kReaders = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;

}  // namespace

SimulationPass::SimulationPass(const Context& ctx, VkDescriptorSetLayout frameLayout, uint64_t storeBytes)
    : ctx_(&ctx) {
  constexpr VkDeviceSize cells = VkDeviceSize{sh::kWindGrid} * sh::kWindGrid;
  blades_ = createBuffer(ctx, cells * sizeof(sh::VirtualBladeGpu), kStateUse, MemoryUse::DeviceLocal,
                         "virtual blades");
  cells_ = createBuffer(ctx, kWindCellsBytes, kStateUse, MemoryUse::DeviceLocal, "wind cells");
  field_ = createBuffer(ctx, kFieldBytes, kStateUse, MemoryUse::DeviceLocal, "interaction field");
  store_ = createBuffer(ctx, std::max<VkDeviceSize>(storeBytes / kTileBytes, 1) * kTileBytes, kStateUse,
                        MemoryUse::DeviceLocal, "trail store");
  for (size_t i = 0; i < blocks_.size(); ++i) {
    blocks_[i] = createBuffer(ctx, sizeof(sh::SimulationParams), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                              MemoryUse::HostUpload, "simulation block (slot " + std::to_string(i) + ")");
    std::memset(blocks_[i].mapped, 0, sizeof(sh::SimulationParams));
  }
  const VkDescriptorSetLayoutBinding bindings[] = {
      {0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
      {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
      {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr}};
  layout_ = createLayout(ctx, bindings, "simulation set layout");
  const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 3}};
  pool_ = createPool(ctx, sizes, 1, "simulation pool");
  set_ = allocateDescriptorSet(ctx, pool_.get(), layout_.get(), "simulation set");
  writeStorageBuffer(ctx, set_, blades_.get(), 0);
  writeStorageBuffer(ctx, set_, cells_.get(), 1);
  writeStorageBuffer(ctx, set_, field_.get(), 2);
  const VkDescriptorSetLayout sets[] = {frameLayout, layout_.get()};
  pipelineLayout_ = createPipelineLayout(ctx, sets, {}, "simulation pipeline layout");
  wind_ = createComputePipeline(ctx, pipelineLayout_.get(), spv_wind_sim_comp, "wind grid pipeline");
  interaction_ = createComputePipeline(ctx, pipelineLayout_.get(), spv_interaction_comp, "interaction field pipeline");
}

void SimulationPass::writeFrameSet(VkDescriptorSet frameSet, int slot) const {
  writeUniformBuffer(*ctx_, frameSet, blocks_[static_cast<size_t>(slot)].get(), sizeof(sh::SimulationParams), 1);
  writeStorageBuffer(*ctx_, frameSet, cells_.get(), 2);
  writeStorageBuffer(*ctx_, frameSet, field_.get(), 3);
}

void SimulationPass::writeBlock(int slot, const simulation::GpuStep* step) {
  void* to = blocks_[static_cast<size_t>(slot)].mapped;
  if (step)
    std::memcpy(to, &step->params, sizeof(sh::SimulationParams));
  else
    std::memset(to, 0, sizeof(sh::SimulationParams));
}

void SimulationPass::record(VkCommandBuffer cmd, VkDescriptorSet frameSet, const simulation::GpuStep& step) {
  // Earlier frames' reads (plants, blades) and writes (the last step) come before this step's.
  memoryBarrier(cmd, kReaders, VK_ACCESS_2_SHADER_READ_BIT | VK_ACCESS_2_SHADER_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT,
                VK_PIPELINE_STAGE_2_TRANSFER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_SHADER_READ_BIT |
                    VK_ACCESS_2_SHADER_WRITE_BIT);
  if (!cleared_ || step.restarted) {  // a new simulation (a new flight, a new driver) starts from nothing
    vkCmdFillBuffer(cmd, blades_.get(), 0, VK_WHOLE_SIZE, 0);
    vkCmdFillBuffer(cmd, cells_.get(), 0, VK_WHOLE_SIZE, 0);
    vkCmdFillBuffer(cmd, field_.get(), 0, VK_WHOLE_SIZE, 0);
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_TRANSFER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                  VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_SHADER_READ_BIT |
                      VK_ACCESS_2_SHADER_WRITE_BIT);
    cleared_ = true;
  }
  // Trails leaving the window go to the store first: an entering tile reuses the same window slot.
  const auto tileAt = [](uint32_t t) { return VkDeviceSize{t} * kTileBytes; };
  const VkDeviceSize storeTiles = store_.size / kTileBytes;
  std::vector<VkBufferCopy> saves, restores;
  for (const simulation::TileTransfer& t : step.transfers) {
    if (t.kind == simulation::TileTransfer::Kind::Save && t.storeSlot < storeTiles)
      saves.push_back({tileAt(t.windowTile), tileAt(t.storeSlot), kTileBytes});
    if (t.kind == simulation::TileTransfer::Kind::Restore && t.storeSlot < storeTiles)
      restores.push_back({tileAt(t.storeSlot), tileAt(t.windowTile), kTileBytes});
  }
  if (!saves.empty()) {
    vkCmdCopyBuffer(cmd, field_.get(), store_.get(), static_cast<uint32_t>(saves.size()), saves.data());
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT);
  }
  if (!restores.empty())
    vkCmdCopyBuffer(cmd, store_.get(), field_.get(), static_cast<uint32_t>(restores.size()), restores.data());
  for (const simulation::TileTransfer& t : step.transfers)
    if (t.kind == simulation::TileTransfer::Kind::Clear ||
        (t.kind == simulation::TileTransfer::Kind::Restore && t.storeSlot >= storeTiles))
      vkCmdFillBuffer(cmd, field_.get(), tileAt(t.windowTile), kTileBytes, 0);
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_READ_BIT | VK_ACCESS_2_SHADER_WRITE_BIT);

  const VkDescriptorSet sets[] = {frameSet, set_};
  if (step.runWind) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, wind_.get());
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelineLayout_.get(), 0, 2, sets, 0, nullptr);
    vkCmdDispatch(cmd, sh::kWindGrid / 8, sh::kWindGrid / 8, 1);
  }
  if (step.runInteraction) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, interaction_.get());
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelineLayout_.get(), 0, 2, sets, 0, nullptr);
    vkCmdDispatch(cmd, sh::kFieldSize / 8, sh::kFieldSize / 8, 1);
  }
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                VK_ACCESS_2_SHADER_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT, kReaders, VK_ACCESS_2_SHADER_READ_BIT);
}

uint64_t SimulationPass::gpuBytes() const {
  uint64_t b = blades_.size + cells_.size + field_.size + store_.size;
  for (const GpuBuffer& u : blocks_) b += u.size;
  return b;
}

}  // namespace vegstream::render
