// The renderer's passes (frame_passes.h): their creation, what a frame writes before it
// records, the passes in order, and the figures they leave once the frame is done.
#include "render/frame_passes.h"

#include <algorithm>
#include <cstring>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include "render/atmosphere_pass.h"
#include "render/blade_pass.h"
#include "render/deletion_queue.h"
#include "render/descriptors.h"
#include "render/frame_uniforms.h"
#include "render/hiz_pass.h"
#include "render/hud_pass.h"
#include "render/plant_marker_pass.h"
#include "render/plant_pass.h"
#include "render/shadow_cascades.h"
#include "render/simulation_pass.h"
#include "render/sky_pass.h"
#include "render/sun_shadow_pass.h"
#include "render/terrain_pass.h"
#include "render/terrain_depth_handover.h"
#include "render/terrain_raster_pass.h"
#include "render/terrain_shade_pass.h"
#include "render/tonemap_pass.h"
#include "render/tree_pass.h"
#include "render/vk_check.h"
#include "vegetation/blade_shape.h"

namespace vegstream::render {

// Every per-slot resource follows the one constant (render/frame_slots.h).
static_assert(HudPass::kSlots == kFramesInFlight, "one HUD buffer set per frame slot");
static_assert(TerrainPass::kSlots == kFramesInFlight, "one terrain buffer set per frame slot");
static_assert(ClassifyPass::kSlots == kFramesInFlight, "one classify (and plant) buffer set per frame slot");
static_assert(TreePass::kSlots == kFramesInFlight, "one tree block per frame slot");

namespace {
constexpr int kBladeTableSegments = vegetation::kBladeShapeSegments;

VkSampleCountFlagBits toSampleBits(int samples) { return static_cast<VkSampleCountFlagBits>(samples); }

// The tone map's settings for a frame: the flat-colour coverage style and an AOV frame pass
// their colours through (identity), a fixed --exposure is fixed, otherwise automatic (smoothed in the window).
ToneSettings toneSettings(const FrameRequest& request) {
  ToneSettings s;
  const bool flat = request.vegetation && request.vegetation->draw.flatColour;
  if (flat || request.aov) {
    s.mode = ToneMode::Identity;
  } else if (request.lighting.exposureEv) {
    s.mode = ToneMode::Fixed;
    s.fixedEv = *request.lighting.exposureEv;
  }
  s.adapt = request.lighting.adaptExposure;
  s.frameSeconds = request.lighting.adaptSeconds;
  return s;
}
}  // namespace

FramePasses::FramePasses(const Context& ctx, VkDescriptorSetLayout frameLayout, RenderTargets& targets,
                         const RendererOptions& options, TerrainShading shading, BladePath bladePath)
    : ctx_(ctx), frameLayout_(frameLayout), targets_(targets), msaa_(options.msaa), bladePath_(bladePath) {
  const bool computeRaster = shading == TerrainShading::Compute;
  const bool deferred = shading == TerrainShading::Deferred || computeRaster;
  simulation_ = std::make_unique<SimulationPass>(ctx, frameLayout, options.trailStoreBytes);
  // The terrain's passes come before the frame sets are written: binding 5 is the compute
  // raster's depth samples (or a placeholder nothing reads: frame.terrainDepth.x is 0 then).
  terrainPass_ = std::make_unique<TerrainPass>(ctx, frameLayout, toSampleBits(msaa_), deferred && !computeRaster,
                                               options.tasks, options.terrainTriangles, options.residentTerrain);
  if (computeRaster) {
    depthHandover_ = std::make_unique<TerrainDepthHandover>(ctx, frameLayout, targets, options.depthTiles);
    terrainRaster_ =
        std::make_unique<TerrainRasterPass>(ctx, frameLayout, *terrainPass_, targets, depthHandover_->tileEdges());
  } else {
    if (deferred) terrainShade_ = std::make_unique<TerrainShadePass>(ctx, frameLayout, *terrainPass_, targets);
    noTerrainDepth_ =
        createBuffer(ctx, 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::DeviceLocal, "terrain depth placeholder");
  }
  hiz_ = std::make_unique<HizPass>(ctx, frameLayout, targets,
                                   computeRaster ? terrainRaster_->depthBuffer() : VK_NULL_HANDLE);
  sunShadows_ = std::make_unique<SunShadowPass>(ctx, std::max(options.shadowMapSize, 64u));
  tonemap_ = std::make_unique<TonemapPass>(ctx, targets);
  atmosphere_ = std::make_unique<AtmospherePass>(ctx);
}

FramePasses::~FramePasses() = default;

void FramePasses::writeFrameSet(VkDescriptorSet set, int slot, bool shadowPass) const {
  const VkBuffer terrainDepth = terrainRaster_ ? terrainRaster_->depthBuffer() : noTerrainDepth_.get();
  simulation_->writeFrameSet(set, slot);
  sunShadows_->writeFrameSet(set, /*placeholder=*/shadowPass);
  writeStorageBuffer(ctx_, set, terrainDepth, 5);
  writeStorageBuffer(ctx_, set, hiz_->pyramid(), 6);
  writeStorageBuffer(ctx_, set, depthHandover_ ? depthHandover_->marks() : noTerrainDepth_.get(), 10);
  atmosphere_->writeFrameSet(set);
}

void FramePasses::createDrawPasses(const RendererOptions& options) {
  sky_ = std::make_unique<SkyPass>(ctx_, frameLayout_, toSampleBits(msaa_));
  hudPass_ = std::make_unique<HudPass>(ctx_);
  ClassifyOptions classifyOptions;
  classifyOptions.tasks = options.tasks;
  classify_ = std::make_unique<ClassifyPass>(ctx_, classifyOptions);
  classify_->setCatalog(vegetation::defaultSpeciesCatalog());
  hiz_->setCatalog(vegetation::defaultSpeciesCatalog());
  markers_ = std::make_unique<PlantMarkerPass>(ctx_, frameLayout_, toSampleBits(msaa_));
  // Species stiffness is relative to the blade's buckling stiffness k_c (the catalog's k′ = 1 is
  // the critical blade, whatever its segment count): the table spans 0.2 … 20 k_c.
  const double kc = vegetation::criticalStiffness(kBladeTableSegments);
  auto table = vegetation::buildBladeShapeTable(kBladeTableSegments, vegetation::kDefaultShapeTableRows, 0.2 * kc,
                                                20.0 * kc, vegetation::kDefaultRootTiltRad);
  // The default table always solves (tests/vegetation/blade_shape_test.cpp); failing is a bug.
  if (!table) throw VulkanError(VK_ERROR_INITIALIZATION_FAILED, "blade shape table: " + table.error().message);
  plantPass_ = std::make_unique<PlantPass>(ctx_, frameLayout_, toSampleBits(msaa_), *table, kc);
  // On a GPU the blade buffers start at their ceiling or half of it (blade_pass.h: each new large
  // buffer stalled the frame thread); on a CPU rasteriser small.
  blades_ = std::make_unique<BladePass>(ctx_, frameLayout_, toSampleBits(msaa_), std::max(options.bladeMaxVertices, 6u),
                                        options.tasks);
  blades_->setCatalog(vegetation::defaultSpeciesCatalog());
  trees_ = std::make_unique<TreePass>(ctx_, frameLayout_, toSampleBits(msaa_), sunShadows_->targetLayout(),
                                      options.treeShadowGroups, options.treeShadowLayers);
}

void FramePasses::prepareFrame(FrameSlot& slot, const FrameRequest& request, uint64_t index) {
  // The overflow thinning's pressure comes from frame index − kFramesInFlight, the slot's last
  // (done now): the same lag however many frames the caller keeps in flight, so recordings stay
  // deterministic (none before the first frames: no pressure).
  classify_->updateThinningFromSlot(slot.submitted && slot.vegetation ? static_cast<int>(index % kFramesInFlight) : -1);
  const VkExtent2D extent = targets_.extent();
  // The trees cast into the sun's shadow map this frame (render/shadow_cascades.h).
  slot.shadows.reset();
  if (request.trees && request.trees->shadows && trees_->modelCount() > 0 && trees_->pageCapacity() > 0) {
    ShadowSettings settings;
    settings.mapSize = sunShadows_->mapSize();
    slot.shadows = shadowCascades(request.camera, double(extent.width) / double(extent.height),
                                  request.lighting.sunDirection, settings);
    shadowRefresh_.plan(*slot.shadows, request.camera.position, request.lighting.sunDirection, index);
  } else {
    shadowRefresh_.reset();
  }
  FrameUniforms u = frameUniforms(request, extent.width, extent.height, slot.shadows ? &*slot.shadows : nullptr);
  // The Hi-Z pyramid is built right after a terrain shaded in compute whenever something tests
  // against it: the trees' impostors (their vertex stage) and the classify's occlusion culling.
  const bool treesDrawn = request.trees && trees_->modelCount() > 0;
  const bool plantsCulled =
      request.vegetation && request.vegetation->occlusionCulling && !request.vegetation->triangles.empty();
  slot.hizEarly = (terrainShade_ || terrainRaster_) && (treesDrawn || plantsCulled);
  const bool marks = depthHandover_ && depthHandover_->mode() != DepthTiles::All;
  u.terrainDepth = glm::vec4(terrainRaster_ ? 1.0f : 0.0f, static_cast<float>(msaa_), slot.hizEarly ? 1.0f : 0.0f,
                             marks ? 1.0f : 0.0f);
  std::memcpy(slot.uniforms.mapped, &u, sizeof(u));
  simulation_->writeBlock(static_cast<int>(index % kFramesInFlight), request.simulation);
}

// The frame's passes, in order: imagery uploads; the terrain's geometry (front to back) — then
// deferred: the visibility scope and the shade (compute, sky included), or forward: scope 1
// with sky and terrain; with plants: the Hi-Z build from the terrain's depth and the classify
// pass (compute, culling the seed triangles the terrain hides), the compute blade expansion,
// then the plants' scope (loading colour and depth, resolving); the HUD over the resolved image.
void FramePasses::record(VkCommandBuffer cmd, FrameSlot& slot, uint64_t index, const FrameRequest& request,
                         DeletionQueue& deletions) {
  const auto retireBuffer = [&](GpuBuffer&& old) { deletions.defer(index, std::move(old)); };
  const int slotIndex = static_cast<int>(index % kFramesInFlight);
  terrainPass_->recordUploads(cmd, slotIndex, request.imageryUploads, retireBuffer);
  slot.vegetation.reset();
  slot.bladesExpanded = false;
  slot.treesDrawn = false;
  const VegetationRequest* plants = request.vegetation;
  const TreeRequest* treeRequest = request.trees && trees_->modelCount() > 0 ? request.trees : nullptr;
  if (depthHandover_) depthHandover_->recordBeginFrame(cmd);  // before the tree classify marks
  if (request.simulation) {  // before anything reads the wind cells or the interaction field
    slot.timer->beginPass(cmd, "simulation");
    simulation_->record(cmd, slot.descriptorSet, *request.simulation);
    slot.timer->endPass(cmd);
  }

  slot.timer->beginPass(cmd, "atmosphere");  // the LUTs and the light every later pass reads
  atmosphere_->record(cmd, request.cameraHeightMsl, glm::vec3(glm::normalize(request.lighting.sunDirection)));
  slot.timer->endPass(cmd);

  // Trees first: classified (compute), then cast into the sun's shadow map, which the terrain,
  // the plants and the trees themselves sample.
  if (treeRequest) recordTreeClassify(cmd, slot, slotIndex, request, *treeRequest, retireBuffer);
  if (slot.shadows) recordShadows(cmd, slot, slotIndex);
  // How the plants' scope starts; the forward terrain's scope resolves when nothing follows it.
  RenderTargets::Load next =
      recordTerrain(cmd, slot, slotIndex, request, plants == nullptr && treeRequest == nullptr, retireBuffer);
  if (slot.hizEarly) {  // the terrain's depth → the Hi-Z pyramid the trees and the classify test against
    slot.timer->beginPass(cmd, "hi-z");
    hiz_->recordBuild(cmd);
    slot.timer->endPass(cmd);
  }
  if (plants) recordPlantsCompute(cmd, slot, slotIndex, *plants, retireBuffer);
  if (depthHandover_) recordDepthHandover(cmd, slot, request);
  if (treeRequest) {  // trees in their own scope, before the plants: they hide much of them
    slot.timer->beginPass(cmd, "trees");
    targets_.beginRendering(cmd, next, /*resolve=*/plants == nullptr, slot.readDepth);
    trees_->recordDraw(cmd, slotIndex, slot.descriptorSet);
    vkCmdEndRendering(cmd);
    slot.timer->endPass(cmd);
    next = RenderTargets::Load::Keep;
  }
  if (plants) {
    recordPlantsDraw(cmd, slot, slotIndex, *plants, next);
  } else if ((terrainShade_ || terrainRaster_) &&
             !treeRequest) {  // no plants: one empty scope resolves the shaded targets
    targets_.beginRendering(cmd, next, /*resolve=*/true, slot.readDepth);
    vkCmdEndRendering(cmd);
  }
  if (terrainRaster_) terrainRaster_->recordEndOfFrame(cmd);
  if (depthHandover_) depthHandover_->recordFigures(cmd, slotIndex);
  slot.timer->beginPass(cmd, "tonemap");
  tonemap_->record(cmd, slotIndex, toneSettings(request), targets_);
  slot.timer->endPass(cmd);
  if (request.overlay) {  // over the resolved image, so read-back and present include it
    slot.timer->beginPass(cmd, "hud");
    hudPass_->record(
        cmd, static_cast<int>(index % kFramesInFlight), *request.overlay, targets_.display(),
        [&](GpuBuffer&& old) { deletions.defer(index, std::move(old)); },
        [&](GpuImage&& old) { deletions.defer(index, std::move(old)); });
    slot.timer->endPass(cmd);
  }
}

// The trees classified (compute) for this frame's view and its shadow cascades.
void FramePasses::recordTreeClassify(VkCommandBuffer cmd, FrameSlot& slot, int slotIndex, const FrameRequest& request,
                                     const TreeRequest& treeRequest, const ClassifyPass::RetireBuffer& retire) {
  slot.timer->beginPass(cmd, "tree classify");
  const VkExtent2D e = targets_.extent();
  const glm::dmat4 viewProj =
      projection(request.camera, double(e.width) / double(e.height)) * viewRotation(request.camera);
  trees_->recordClassify(cmd, slotIndex, slot.descriptorSet, treeRequest, viewProj,
                         treeLodScale(e.height, request.camera.verticalFovDeg), slot.shadows ? 40.0f : 0.0f, retire);
  slot.timer->endPass(cmd);
  slot.treesDrawn = true;
}

// The trees cast into the sun's shadow map's cascades (slot.shadows).
void FramePasses::recordShadows(VkCommandBuffer cmd, FrameSlot& slot, int slotIndex) {
  slot.timer->beginPass(cmd, "shadow");
  sunShadows_->record(cmd, *slot.shadows,
                      [&](VkCommandBuffer c, int cascade, const glm::mat4& m, VkDescriptorSet target) {
                        trees_->recordShadow(c, slotIndex, slot.shadowPassSet, cascade, m,
                                             slot.shadows->texelM[size_t(cascade)], target);
                      });
  slot.timer->endPass(cmd);
}

// The terrain: rasterised and shaded in compute, deferred (ids, then shaded in compute, sky
// included) or forward (sky and terrain in one scope, resolved when lastScope). Returns how the
// next scope starts.
RenderTargets::Load FramePasses::recordTerrain(VkCommandBuffer cmd, FrameSlot& slot, int slotIndex,
                                               const FrameRequest& request, bool lastScope,
                                               const ClassifyPass::RetireBuffer& retire) {
  slot.terrainTriangles = terrainPass_->prepare(cmd, slotIndex, request.camera.position, request.terrain, retire);
  slot.terrainGeometry = terrainPass_->geometryFigures();
  if (terrainRaster_) {  // rasterised and shaded in compute: no graphics work for the terrain
    slot.timer->beginPass(cmd, "terrain");
    terrainRaster_->record(cmd, slotIndex, slot.descriptorSet, *terrainPass_, targets_, slot.terrainTriangles, retire,
                           [&] {
                             slot.timer->endPass(cmd);
                             slot.timer->beginPass(cmd, "terrain shade");
                           });
    slot.timer->endPass(cmd);
    return RenderTargets::Load::Shaded;  // its depth goes into the attachment later: recordDepthHandover
  } else if (terrainShade_) {            // deferred: triangle ids, then every pixel shaded in compute (sky included)
    slot.timer->beginPass(cmd, "terrain");
    targets_.beginVisibility(cmd);
    terrainPass_->recordVisibility(cmd, slotIndex, slot.descriptorSet);
    vkCmdEndRendering(cmd);
    slot.timer->endPass(cmd);
    slot.timer->beginPass(cmd, "terrain shade");
    targets_.visibilityToShade(cmd);
    terrainShade_->record(cmd, slotIndex, slot.descriptorSet, *terrainPass_, targets_);
    slot.timer->endPass(cmd);
    return RenderTargets::Load::Shaded;
  } else {
    targets_.beginRendering(cmd, RenderTargets::Load::Clear, /*resolve=*/lastScope, slot.readDepth);
    slot.timer->beginPass(cmd, "sky");
    sky_->record(cmd, slot.descriptorSet);
    slot.timer->endPass(cmd);
    slot.timer->beginPass(cmd, "terrain");
    terrainPass_->recordForward(cmd, slotIndex, slot.descriptorSet);
    slot.timer->endPass(cmd);
    vkCmdEndRendering(cmd);
  }
  return RenderTargets::Load::Keep;
}

// After the terrain: Hi-Z build + classify (culling hidden seed triangles when asked, marking
// where the plants that may show are drawn), the compute blade expansion.
void FramePasses::recordPlantsCompute(VkCommandBuffer cmd, FrameSlot& slot, int slotIndex,
                                      const VegetationRequest& plants, const ClassifyPass::RetireBuffer& retire) {
  const uint32_t patchMask = drawnSpecies(plants);
  slot.timer->beginPass(cmd, "classify");
  classify_->setFades(plants.draw.fades);
  ClassifyPass::CullHook cull;
  if (plants.occlusionCulling && !plants.triangles.empty()) {
    if (!slot.hizEarly) hiz_->recordBuild(cmd);
    cull = [&](VkCommandBuffer c, VkBuffer triangles, VkBuffer visible, uint32_t count) {
      hiz_->recordCull(c, slotIndex, slot.descriptorSet, triangles, visible, count, plants.clusterSize,
                       plants.draw.shadows && plants.style == PlantStyle::Plants, patchMask);
    };
  }
  slot.vegetation =
      classify_->record(cmd, slotIndex, plants.triangles, plants.clusterSize, terrainPass_->imageryBytesView(),
                        terrainPass_->companionView(), terrainPass_->companions().flags(),
                        PlantMarkerPass::verticesPerGroup(plants.clusterSize), patchMask, retire, cull, plants.canopy);
  slot.vegetation->occlusionCulling = plants.occlusionCulling;  // counts stay 0 without triangles
  slot.timer->endPass(cmd);
  // The compute blade path expands the plants before their scope (render/blade_pass.h).
  slot.bladesExpanded = plants.style == PlantStyle::Plants && pathFor(plants.draw) == BladePath::Compute;
  if (slot.bladesExpanded) {
    slot.timer->beginPass(cmd, "blades");
    blades_->recordExpand(cmd, slotIndex, slot.descriptorSet, *classify_, *plantPass_, plants.triangles,
                          plants.clusterSize, terrainPass_->imageryView(), plants.draw, retire);
    slot.timer->endPass(cmd);
  }
}

// Before the trees' and the plants' scopes, after everything that marks where they are drawn.
void FramePasses::recordDepthHandover(VkCommandBuffer cmd, FrameSlot& slot, const FrameRequest& request) {
  // Every tile where nothing marks the plants (the Hi-Z cull marks them: without it, or for
  // markers, nothing does) or where the frame's depth is read back.
  const VegetationRequest* plants = request.vegetation;
  const bool unmarked =
      plants && !plants->triangles.empty() && (!plants->occlusionCulling || plants->style == PlantStyle::Markers);
  slot.timer->beginPass(cmd, "terrain depth");
  depthHandover_->record(cmd, slot.descriptorSet, targets_, unmarked || slot.readDepth);
  slot.timer->endPass(cmd);
}

// The plants' scope: loads the terrain's (and the trees') colour and depth and resolves.
void FramePasses::recordPlantsDraw(VkCommandBuffer cmd, FrameSlot& slot, int slotIndex, const VegetationRequest& plants,
                                   RenderTargets::Load load) {
  const uint32_t patchMask = drawnSpecies(plants);
  targets_.beginRendering(cmd, load, /*resolve=*/true, slot.readDepth);
  if (plants.style != PlantStyle::Hidden) {
    slot.timer->beginPass(cmd, "plants");
    if (patchMask != 0 && slot.bladesExpanded)
      blades_->recordDraw(cmd, slotIndex, slot.descriptorSet);
    else if (patchMask != 0)
      plantPass_->record(cmd, slotIndex, slot.descriptorSet, *classify_, terrainPass_->imageryView(), plants.draw);
    // Tree species are not plants (render/tree_pass.h draws them, classify rejects them as bare):
    // `--plant-style markers` draws every other species' marker (patchMask is 0 then).
    if (plants.style == PlantStyle::Markers)
      markers_->record(cmd, slotIndex, slot.descriptorSet, *classify_, patchMask);
    slot.timer->endPass(cmd);
  }
  vkCmdEndRendering(cmd);
}

uint32_t FramePasses::drawnSpecies(const VegetationRequest& plants) const {
  return plants.style == PlantStyle::Plants ? PlantPass::patchMask(*classify_) : 0u;
}

BladePath FramePasses::pathFor(const PlantDrawOptions& draw) const {
  if (draw.speedOfLight) return BladePath::Tessellation;
  return draw.path == BladePath::Auto ? bladePath_ : draw.path;
}

void FramePasses::readFigures(FrameSlot& slot, FrameResult& r) const {
  const int slotIndex = static_cast<int>(slot.frameIndex % kFramesInFlight);
  r.terrainChunksDrawn = slot.terrainGeometry.chunksDrawn;
  r.terrainChunksUploaded = slot.terrainGeometry.chunksUploaded;
  r.terrainVerticesUploaded = slot.terrainGeometry.verticesUploaded;
  r.terrainRasterised = terrainRaster_ != nullptr;
  if (terrainRaster_) {
    const TerrainRasterFigures f = terrainRaster_->figures(slotIndex);
    r.terrainRasterTriangles = f.rasterTriangles;
    r.terrainTileEntries = f.tileEntries;
    r.terrainTileEntriesDropped = f.tileEntriesDropped;
    const DepthHandoverFigures d = depthHandover_->figures(slotIndex);
    r.terrainDepthTiles = d.pixelTiles;
    r.terrainDepthEdgeTiles = d.edgeTiles;
  }
  if (slot.vegetation) {
    classify_->readFigures(slotIndex, *slot.vegetation);
    if (slot.vegetation->occlusionCulling && slot.vegetation->seedTriangles > 0)  // the test ran
      hiz_->readFigures(slotIndex, *slot.vegetation);
    if (slot.bladesExpanded) blades_->readFigures(slotIndex, *slot.vegetation);
    r.vegetation = slot.vegetation;
  }
  if (slot.treesDrawn) r.trees = trees_->figures(slotIndex);
  r.exposureEv = tonemap_->exposureEv(slotIndex);
}

void FramePasses::setCatalog(const vegetation::SpeciesCatalog& catalog) {
  classify_->setCatalog(catalog);
  terrainPass_->setTerrainTypes(vegetation::terrainTypesOf(catalog));
  hiz_->setCatalog(catalog);
  blades_->setCatalog(catalog);
}

uint64_t FramePasses::gpuBytes() const {
  return terrainPass_->gpuBytes() + classify_->gpuBytes() + plantPass_->gpuBytes() + hiz_->gpuBytes() +
         blades_->gpuBytes() + simulation_->gpuBytes() + trees_->gpuBytes() + sunShadows_->gpuBytes() +
         (terrainRaster_ ? terrainRaster_->gpuBytes() + depthHandover_->gpuBytes() : 0);
}

}  // namespace vegstream::render
