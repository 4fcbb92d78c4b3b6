#pragma once
// Private to render/: the renderer's passes and the one order a frame records them in. Owns every
// pass (sky, terrain and its deferred shade or compute raster, Hi-Z, classify, markers, the
// tessellation and compute blade paths, trees, sun shadows, simulation, atmosphere, tone map,
// HUD) and what the passes share across frames (the shadow cascades' refresh plan).
//
// Contract: made in two steps, in the renderer's creation order — the constructor makes the
// passes set 0 of every frame refers to (writeFrameSet writes their bindings), createDrawPasses
// the rest once the frame sets are written; no frame is recorded before both. A frame is
// prepareFrame (uniforms and simulation block into its slot), then record (its passes into the
// slot's command buffer, in order), then, once its fence has signalled, readFigures. Frames are
// prepared and recorded in index order (the shadow refresh plan follows them).

#include <cstdint>
#include <memory>

#include "render/classify_pass.h"
#include "render/frame_slot.h"
#include "render/gpu_resources.h"
#include "render/render_targets.h"
#include "render/renderer.h"
#include "render/shadow_refresh.h"

namespace vegstream::render {

class AtmospherePass;
class BladePass;
class DeletionQueue;
class HizPass;
class HudPass;
class PlantMarkerPass;
class PlantPass;
class SimulationPass;
class SkyPass;
class SunShadowPass;
class TerrainPass;
class TerrainDepthHandover;
class TerrainRasterPass;
class TerrainShadePass;
class TonemapPass;
class TreePass;

class FramePasses {
 public:
  // The passes set 0 refers to, for `shading` (Forward, Deferred or Compute: resolved) at
  // options.msaa samples. `targets` must outlive the passes.
  FramePasses(const Context& ctx, VkDescriptorSetLayout frameLayout, RenderTargets& targets,
              const RendererOptions& options, TerrainShading shading, BladePath bladePath);
  ~FramePasses();
  FramePasses(const FramePasses&) = delete;
  FramePasses& operator=(const FramePasses&) = delete;

  // Set 0's bindings after the uniforms (1–6) for frame slot `slot`: the shadow pass's own set
  // (`shadowPass`) gets a placeholder shadow map at binding 4.
  void writeFrameSet(VkDescriptorSet set, int slot, bool shadowPass) const;
  // The sky, the HUD and the passes of the plants and trees, after the frame sets are written.
  void createDrawPasses(const RendererOptions& options);

  // Before frame `index` is recorded in `slot` (done with its last frame): the classify's
  // overflow thinning from the slot's last frame, the frame's sun shadow cascades, uniforms and
  // simulation block.
  void prepareFrame(FrameSlot& slot, const FrameRequest& request, uint64_t index);
  // Frame `index`'s passes into cmd, in order; what a pass replaces is retired into `deletions`
  // as used up to this frame.
  void record(VkCommandBuffer cmd, FrameSlot& slot, uint64_t index, const FrameRequest& request,
              DeletionQueue& deletions);
  // The passes' figures of the slot's frame (done on the GPU) into r; the slot's vegetation
  // figures are completed in place.
  void readFigures(FrameSlot& slot, FrameResult& r) const;

  // The species every later frame sorts plants into (the classify, the terrain's types, the
  // Hi-Z reach, the blades); no frame may be in flight.
  void setCatalog(const vegetation::SpeciesCatalog& catalog);
  uint64_t gpuBytes() const;  // the scene's buffers and textures (targets excluded)
  TerrainPass& terrain() { return *terrainPass_; }
  const TerrainPass& terrain() const { return *terrainPass_; }
  const SimulationPass& simulation() const { return *simulation_; }
  const BladePass& blades() const { return *blades_; }
  TreePass& trees() { return *trees_; }
  const TreePass& trees() const { return *trees_; }
  const SunShadowPass& sunShadows() const { return *sunShadows_; }
  const AtmospherePass& atmosphere() const { return *atmosphere_; }

 private:
  // The path a frame's plants take: the speed-of-light pipeline is a tessellation pipeline.
  BladePath pathFor(const PlantDrawOptions& draw) const;
  // The species the plant pipelines draw this frame (bits; 0 for markers or hidden plants).
  uint32_t drawnSpecies(const VegetationRequest& plants) const;
  void recordTreeClassify(VkCommandBuffer cmd, FrameSlot& slot, int slotIndex, const FrameRequest& request,
                          const TreeRequest& treeRequest, const ClassifyPass::RetireBuffer& retire);
  void recordShadows(VkCommandBuffer cmd, FrameSlot& slot, int slotIndex);
  RenderTargets::Load recordTerrain(VkCommandBuffer cmd, FrameSlot& slot, int slotIndex, const FrameRequest& request,
                                    bool lastScope, const ClassifyPass::RetireBuffer& retire);
  // The plants' compute work (classify, culling, blade expansion), before the terrain's depth is
  // handed over; then their scope.
  void recordPlantsCompute(VkCommandBuffer cmd, FrameSlot& slot, int slotIndex, const VegetationRequest& plants,
                           const ClassifyPass::RetireBuffer& retire);
  void recordPlantsDraw(VkCommandBuffer cmd, FrameSlot& slot, int slotIndex, const VegetationRequest& plants,
                        RenderTargets::Load load);
  // The terrain's depth samples into the depth attachment where plants or trees may be drawn.
  void recordDepthHandover(VkCommandBuffer cmd, FrameSlot& slot, const FrameRequest& request);

  const Context& ctx_;
  VkDescriptorSetLayout frameLayout_;
  RenderTargets& targets_;
  int msaa_;
  BladePath bladePath_;  // resolved: never Auto or Mesh
  std::unique_ptr<SimulationPass> simulation_;
  std::unique_ptr<TerrainPass> terrainPass_;
  std::unique_ptr<TerrainShadePass> terrainShade_;       // deferred terrain shading only
  std::unique_ptr<TerrainRasterPass> terrainRaster_;     // the terrain rasterised in compute only
  std::unique_ptr<TerrainDepthHandover> depthHandover_;  // with terrainRaster_
  // Set 0 bindings 5 and 10 when the depth attachment holds the terrain (nothing reads or marks them).
  GpuBuffer noTerrainDepth_;
  std::unique_ptr<HizPass> hiz_;
  std::unique_ptr<SunShadowPass> sunShadows_;
  std::unique_ptr<TonemapPass> tonemap_;
  std::unique_ptr<AtmospherePass> atmosphere_;
  std::unique_ptr<SkyPass> sky_;
  std::unique_ptr<HudPass> hudPass_;
  std::unique_ptr<ClassifyPass> classify_;
  std::unique_ptr<PlantMarkerPass> markers_;
  std::unique_ptr<PlantPass> plantPass_;
  std::unique_ptr<BladePass> blades_;
  std::unique_ptr<TreePass> trees_;
  ShadowRefresh shadowRefresh_;  // which cascades each frame draws again (frames are recorded in order)
};

}  // namespace vegstream::render
