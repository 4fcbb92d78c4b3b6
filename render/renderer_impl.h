#pragma once
// Private to render/: the renderer's implementation (frame slots, passes, targets), shared by
// renderer.cpp (creation, submit, the public API) and frame_passes.cpp (what one frame
// records: the passes in order, read-back, present, submission, collect).

#include "render/renderer.h"

#include <memory>
#include <optional>
#include <algorithm>
#include <array>
#include <cstring>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include "core/stopwatch.h"
#include "vegetation/blade_shape.h"
#include "render/blade_pass.h"
#include "render/deletion_queue.h"
#include "render/descriptors.h"
#include "render/frame_slot.h"
#include "render/frame_slots.h"
#include "render/frame_uniforms.h"
#include "render/gpu_timer.h"
#include "render/hiz_pass.h"
#include "render/hud_pass.h"
#include "render/render_targets.h"
#include "render/classify_pass.h"
#include "render/plant_marker_pass.h"
#include "render/plant_pass.h"
#include "render/simulation_pass.h"
#include "render/sky_pass.h"
#include "render/swapchain.h"
#include "render/terrain_detail.h"
#include "render/terrain_pass.h"
#include "render/shadow_cascades.h"
#include "render/shadow_refresh.h"
#include "render/sun_shadow_pass.h"
#include "render/terrain_raster_pass.h"
#include "render/terrain_shade_pass.h"
#include "render/tonemap_pass.h"
#include "render/atmosphere_pass.h"
#include "render/tree_impostors.h"
#include "render/tree_pass.h"
#include "render/vk_check.h"

namespace vegstream::render {

// Every per-slot resource follows the one constant (render/frame_slots.h).
static_assert(HudPass::kSlots == kFramesInFlight, "one HUD buffer set per frame slot");
static_assert(TerrainPass::kSlots == kFramesInFlight, "one terrain buffer set per frame slot");
static_assert(ClassifyPass::kSlots == kFramesInFlight, "one classify (and plant) buffer set per frame slot");
static_assert(TreePass::kSlots == kFramesInFlight, "one tree block per frame slot");
inline constexpr int kBladeTableSegments = vegetation::kBladeShapeSegments;

inline VkSampleCountFlagBits toSampleBits(int samples) { return static_cast<VkSampleCountFlagBits>(samples); }

struct Renderer::Impl {
  std::unique_ptr<Context> ctx;
  std::shared_ptr<ValidationLog> validationLog;
  std::unique_ptr<RenderTargets> targets;
  std::unique_ptr<TonemapPass> tonemap;
  std::unique_ptr<AtmospherePass> atmosphere;
  std::unique_ptr<Swapchain> swapchain;
  DescriptorSetLayout frameLayout;
  DescriptorPool descriptorPool;
  std::unique_ptr<SkyPass> sky;
  std::unique_ptr<TerrainPass> terrainPass;
  std::unique_ptr<TerrainShadePass> terrainShade;  // deferred terrain shading only
  std::unique_ptr<TerrainRasterPass> terrainRaster;  // the terrain rasterised in compute only
  GpuBuffer noTerrainDepth;  // set 0 binding 5 when the depth attachment holds the terrain
  std::unique_ptr<HudPass> hudPass;
  std::unique_ptr<ClassifyPass> classify;
  std::unique_ptr<HizPass> hiz;
  std::unique_ptr<PlantMarkerPass> markers;
  std::unique_ptr<PlantPass> plantPass;
  std::unique_ptr<BladePass> blades;
  std::unique_ptr<SimulationPass> simulation;
  std::unique_ptr<TreePass> trees;
  std::unique_ptr<SunShadowPass> sunShadows;
  ShadowRefresh shadowRefresh;  // which cascades each frame draws again (frames are recorded in order)
  uint64_t treeBudgetBytes = 0;
  BladePath bladePath = BladePath::Compute;  // resolved: never Auto or Mesh
  std::array<FrameSlot, kFramesInFlight> slots;
  DeletionQueue deletions;
  uint64_t nextFrame = 1;       // frame indices start at 1; 0 means "none"
  uint64_t completedFrame = 0;  // highest frame known finished on the GPU
  int msaa = 1;
  TerrainShading terrainShading = TerrainShading::Forward;

  ~Impl() {
    if (ctx) vkDeviceWaitIdle(ctx->device());
    deletions.collectAll();
  }

  void init(const RendererOptions& options);
  void initFrameSlots(VkDeviceSize pixels, VkBuffer terrainDepth);
  void initPlantPasses(const RendererOptions& options);
  void waitSlot(FrameSlot& slot);
  void writeFrameState(FrameSlot& slot, const FrameRequest& request, uint64_t index);
  uint64_t submit(const FrameRequest& request);
  void recordPasses(VkCommandBuffer cmd, FrameSlot& slot, uint64_t index, const FrameRequest& request);
  void recordTreeClassify(VkCommandBuffer cmd, FrameSlot& slot, int slotIndex, const FrameRequest& request,
                          const TreeRequest& treeRequest, const ClassifyPass::RetireBuffer& retire);
  void recordShadows(VkCommandBuffer cmd, FrameSlot& slot, int slotIndex);
  RenderTargets::Load recordTerrain(VkCommandBuffer cmd, FrameSlot& slot, int slotIndex, const FrameRequest& request,
                                    bool lastScope, const ClassifyPass::RetireBuffer& retire);
  void recordPlants(VkCommandBuffer cmd, FrameSlot& slot, int slotIndex, const VegetationRequest& plants,
                    RenderTargets::Load load, const ClassifyPass::RetireBuffer& retire);
  void queueSubmit(FrameSlot& slot, std::optional<uint32_t> imageIndex);
  void recordReadback(VkCommandBuffer cmd, FrameSlot& slot, bool color, bool depth) const;
  // An AOV frame's resolved float target (left in the general layout by the tone map) → aovReadback.
  void recordAovReadback(VkCommandBuffer cmd, FrameSlot& slot) const;
  void recordPresent(VkCommandBuffer cmd, uint32_t imageIndex) const;
  FrameResult collect(FrameSlot& slot);
  // The path a frame's plants take: the speed-of-light pipeline is a tessellation pipeline.
  BladePath pathFor(const PlantDrawOptions& draw) const {
    if (draw.speedOfLight) return BladePath::Tessellation;
    return draw.path == BladePath::Auto ? bladePath : draw.path;
  }
};

}  // namespace vegstream::render
