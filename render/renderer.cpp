// The renderer (renderer.h, Renderer::Impl in renderer_impl.h): its creation from the options
// and the device, its passes and frame slots, submitting a frame, and the public
// API's setters and debug read-backs. What a frame records is frame_passes.cpp.
#include "render/renderer.h"

#include "render/renderer_impl.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

namespace vegstream::render {

void Renderer::Impl::init(const RendererOptions& options) {
  const VkExtent2D extent{options.width, options.height};
  const bool computeRaster = terrainShading == TerrainShading::Compute;
  const bool deferred = terrainShading == TerrainShading::Deferred || computeRaster;
  targets = std::make_unique<RenderTargets>(*ctx, extent, toSampleBits(msaa), deferred, computeRaster);
  if (options.window) swapchain = std::make_unique<Swapchain>(*ctx, options.window);
  frameLayout = createFrameSetLayout(*ctx);
  descriptorPool = createFrameSetPool(*ctx);
  const VkDescriptorSetLayout layout = frameLayout.get();

  simulation = std::make_unique<SimulationPass>(*ctx, layout, options.trailStoreBytes);
  // The terrain's passes come before the frame sets are written: binding 5 is the compute
  // raster's depth samples (or a placeholder nothing reads: frame.terrainDepth.x is 0 then).
  terrainPass = std::make_unique<TerrainPass>(*ctx, layout, toSampleBits(msaa), deferred && !computeRaster,
                                              options.tasks, options.terrainTriangles);
  if (computeRaster) {
    terrainRaster = std::make_unique<TerrainRasterPass>(*ctx, layout, *terrainPass, *targets);
  } else {
    if (deferred) terrainShade = std::make_unique<TerrainShadePass>(*ctx, layout, *terrainPass, *targets);
    noTerrainDepth = createBuffer(*ctx, 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::DeviceLocal,
                                  "terrain depth placeholder");
  }
  const VkBuffer terrainDepth = computeRaster ? terrainRaster->depthBuffer() : noTerrainDepth.get();
  hiz = std::make_unique<HizPass>(*ctx, layout, *targets, computeRaster ? terrainDepth : VK_NULL_HANDLE);
  sunShadows = std::make_unique<SunShadowPass>(*ctx, std::max(options.shadowMapSize, 64u));
  tonemap = std::make_unique<TonemapPass>(*ctx, *targets);
  atmosphere = std::make_unique<AtmospherePass>(*ctx);
  initFrameSlots(VkDeviceSize{extent.width} * extent.height, terrainDepth);
  initPlantPasses(options);
  treeBudgetBytes = options.treeBudgetBytes;
}

// Every slot's resources (frame_slot.h) and its two frame sets: the second is the shadow pass's,
// its binding 4 a placeholder map.
void Renderer::Impl::initFrameSlots(VkDeviceSize pixels, VkBuffer terrainDepth) {
  const VkDescriptorSetLayout layout = frameLayout.get();
  for (int i = 0; i < kFramesInFlight; ++i) {
    FrameSlot& s = slots[static_cast<size_t>(i)];
    createFrameSlot(*ctx, s, i, pixels);
    const std::string tag = " (slot " + std::to_string(i) + ")";
    s.descriptorSet = allocateDescriptorSet(*ctx, descriptorPool.get(), layout, "frame uniforms set" + tag);
    writeUniformBuffer(*ctx, s.descriptorSet, s.uniforms.get(), sizeof(FrameUniforms));
    simulation->writeFrameSet(s.descriptorSet, i);
    sunShadows->writeFrameSet(s.descriptorSet);
    writeStorageBuffer(*ctx, s.descriptorSet, terrainDepth, 5);
    writeStorageBuffer(*ctx, s.descriptorSet, hiz->pyramid(), 6);
    atmosphere->writeFrameSet(s.descriptorSet);
    s.shadowPassSet = allocateDescriptorSet(*ctx, descriptorPool.get(), layout, "shadow pass frame set" + tag);
    writeUniformBuffer(*ctx, s.shadowPassSet, s.uniforms.get(), sizeof(FrameUniforms));
    simulation->writeFrameSet(s.shadowPassSet, i);
    sunShadows->writeFrameSet(s.shadowPassSet, /*placeholder=*/true);
    writeStorageBuffer(*ctx, s.shadowPassSet, terrainDepth, 5);
    writeStorageBuffer(*ctx, s.shadowPassSet, hiz->pyramid(), 6);
    atmosphere->writeFrameSet(s.shadowPassSet);
  }
}

// The sky, the HUD and the passes of the plants and trees, after the frame sets are written.
void Renderer::Impl::initPlantPasses(const RendererOptions& options) {
  const VkDescriptorSetLayout layout = frameLayout.get();
  sky = std::make_unique<SkyPass>(*ctx, layout, toSampleBits(msaa));
  hudPass = std::make_unique<HudPass>(*ctx);
  ClassifyOptions classifyOptions;
  classifyOptions.tasks = options.tasks;
  classify = std::make_unique<ClassifyPass>(*ctx, classifyOptions);
  classify->setCatalog(vegetation::defaultSpeciesCatalog());
  hiz->setCatalog(vegetation::defaultSpeciesCatalog());
  markers = std::make_unique<PlantMarkerPass>(*ctx, layout, toSampleBits(msaa));
  // Species stiffness is relative to the blade's buckling stiffness k_c (the catalog's k′ = 1 is
  // the critical blade, whatever its segment count): the table spans 0.2 … 20 k_c.
  const double kc = vegetation::criticalStiffness(kBladeTableSegments);
  auto table = vegetation::buildBladeShapeTable(kBladeTableSegments, vegetation::kDefaultShapeTableRows, 0.2 * kc,
                                                20.0 * kc, vegetation::kDefaultRootTiltRad);
  // The default table always solves (tests/vegetation/blade_shape_test.cpp); failing is a bug.
  if (!table) throw VulkanError(VK_ERROR_INITIALIZATION_FAILED, "blade shape table: " + table.error().message);
  plantPass = std::make_unique<PlantPass>(*ctx, layout, toSampleBits(msaa), *table, kc);
  // On a GPU the blade buffers start at their ceiling or half of it (blade_pass.h: each new large
  // buffer stalled the frame thread); on a CPU rasteriser small.
  blades = std::make_unique<BladePass>(*ctx, layout, toSampleBits(msaa), std::max(options.bladeMaxVertices, 6u),
                                       options.tasks);
  blades->setCatalog(vegetation::defaultSpeciesCatalog());
  trees = std::make_unique<TreePass>(*ctx, layout, toSampleBits(msaa));
}

void Renderer::Impl::waitSlot(FrameSlot& slot) {
  if (!slot.submitted) return;
  VkFence fence = slot.fence.get();
  vkCheck(vkWaitForFences(ctx->device(), 1, &fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
  // A fence's signal covers every command submitted before it on the queue, so frame F done
  // means every frame up to F is done, whichever slot was waited for first (waitFrame may take
  // the frames in flight in any order): the deletion queue retires by that number.
  completedFrame = std::max(completedFrame, slot.frameIndex);
  deletions.collect(completedFrame);
}

// The frame's sun shadow cascades, uniforms and simulation block, into its slot.
void Renderer::Impl::writeFrameState(FrameSlot& slot, const FrameRequest& request, uint64_t index) {
  const VkExtent2D extent = targets->extent();
  // The trees cast into the sun's shadow map this frame (render/shadow_cascades.h).
  slot.shadows.reset();
  if (request.trees && request.trees->shadows && trees->modelCount() > 0 && trees->pageCapacity() > 0) {
    ShadowSettings settings;
    settings.mapSize = sunShadows->mapSize();
    slot.shadows = shadowCascades(request.camera, double(extent.width) / double(extent.height),
                                  request.lighting.sunDirection, settings);
    shadowRefresh.plan(*slot.shadows, request.camera.position, request.lighting.sunDirection, index);
  } else {
    shadowRefresh.reset();
  }
  FrameUniforms u = frameUniforms(request, extent.width, extent.height, slot.shadows ? &*slot.shadows : nullptr);
  // The Hi-Z pyramid is built right after a terrain shaded in compute whenever something tests
  // against it: the trees' impostors (their vertex stage) and the classify's occlusion culling.
  const bool treesDrawn = request.trees && trees->modelCount() > 0;
  const bool plantsCulled = request.vegetation && request.vegetation->occlusionCulling &&
                            !request.vegetation->triangles.empty();
  slot.hizEarly = (terrainShade || terrainRaster) && (treesDrawn || plantsCulled);
  u.terrainDepth = glm::vec4(terrainRaster ? 1.0f : 0.0f, static_cast<float>(msaa), slot.hizEarly ? 1.0f : 0.0f, 0.0f);
  std::memcpy(slot.uniforms.mapped, &u, sizeof(u));
  simulation->writeBlock(static_cast<int>(index % kFramesInFlight), request.simulation);
}

uint64_t Renderer::Impl::submit(const FrameRequest& request) {
  Stopwatch watch;
  const uint64_t index = nextFrame++;
  FrameSlot& slot = slots[index % kFramesInFlight];
  waitSlot(slot);
  // The overflow thinning's pressure comes from frame index − kFramesInFlight, the slot's last
  // (done now): the same lag however many frames the caller keeps in flight, so recordings stay
  // deterministic (none before the first frames: no pressure).
  classify->updateThinningFromSlot(slot.submitted && slot.vegetation ? static_cast<int>(index % kFramesInFlight) : -1);
  VkFence fence = slot.fence.get();
  vkCheck(vkResetFences(ctx->device(), 1, &fence), "vkResetFences");

  writeFrameState(slot, request, index);
  const VkExtent2D extent = targets->extent();

  std::optional<uint32_t> imageIndex;
  if (request.present && swapchain) imageIndex = swapchain->acquire(slot.imageAcquired.get());

  vkCheck(vkResetCommandPool(ctx->device(), slot.pool.get(), 0), "vkResetCommandPool");
  VkCommandBuffer cmd = slot.cmd;
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  vkCheck(vkBeginCommandBuffer(cmd, &bi), "vkBeginCommandBuffer");
  slot.timer->begin(cmd);
  slot.readAov = request.aov;
  if (request.aov && !slot.aovReadback.get())  // one packed-float texel (4 bytes) a pixel; the slot's frame is done (waitSlot)
    slot.aovReadback = createBuffer(*ctx, size_t{extent.width} * extent.height * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                    MemoryUse::HostReadback, "AOV read-back");
  slot.readColor = request.readbackColor && !request.aov;
  slot.readDepth = request.readbackDepth || request.aov;  // recordPasses resolves the depth only for it
  if (request.aov)
    slot.aovInverseProjection =
        glm::inverse(projection(request.camera, double(extent.width) / double(extent.height)));
  recordPasses(cmd, slot, index, request);
  recordReadback(cmd, slot, slot.readColor, slot.readDepth);
  if (slot.readAov) recordAovReadback(cmd, slot);
  if (imageIndex) recordPresent(cmd, *imageIndex);
  slot.timer->end(cmd);
  vkCheck(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");

  queueSubmit(slot, imageIndex);
  if (imageIndex) swapchain->present(*imageIndex, swapchain->renderDone(*imageIndex));

  slot.frameIndex = index;
  slot.submitted = true;
  slot.cpuRecordMs = watch.elapsedMs();
  return index;
}

// --- public API ---------------------------------------------------------------------------

Renderer::Renderer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Renderer::~Renderer() = default;

Result<std::unique_ptr<Renderer>> Renderer::create(const RendererOptions& options) {
  ContextOptions co = options.context;
  if (options.window) {
    uint32_t n = 0;
    const char** names = glfwGetRequiredInstanceExtensions(&n);
    if (!names) return makeError(ErrorKind::Unsupported, "the window system offers no Vulkan surface (GLFW)");
    for (uint32_t i = 0; i < n; ++i) co.instanceExtensions.emplace_back(names[i]);
    co.wantSwapchain = true;
  }
  auto ctx = Context::create(co);
  if (!ctx) return ctx.error();
  auto impl = std::make_unique<Impl>();
  impl->ctx = std::move(*ctx);
  impl->validationLog = co.validationLog;

  const auto& info = impl->ctx->info();
  const uint32_t maxDim = impl->ctx->properties().limits.maxImageDimension2D;
  if (options.width == 0 || options.height == 0 || options.width > maxDim || options.height > maxDim)
    return makeError(ErrorKind::InvalidInput, "--size " + std::to_string(options.width) + "x" +
                                                  std::to_string(options.height) + " is impossible on " + info.name +
                                                  ": each side must be 1 … " + std::to_string(maxDim) + " pixels");
  if (!info.supportsMsaa(options.msaa))
    return makeError(ErrorKind::InvalidInput, "--msaa " + std::to_string(options.msaa) + " is not offered by " +
                                                  info.name + "; choose one of " + info.msaaList());
  impl->msaa = options.msaa;
  Result<TerrainShading> shading = resolveTerrainShading(options.terrainShading, info, options.msaa);
  if (!shading) return shading.error();
  impl->terrainShading = *shading;
  // This build has no mesh-shader blade path (VK_EXT_mesh_shader): refused before any frame.
  if (options.bladePath == BladePath::Mesh)
    return makeError(ErrorKind::InvalidInput,
                     "--blade-path mesh is not available on " + info.name +
                         ": this build has no mesh-shader (VK_EXT_mesh_shader) blade path; use auto, compute or "
                         "tessellation");
  // Auto: compute, which every Vulkan device has and which keeps per-blade work off the graphics stages.
  impl->bladePath = options.bladePath == BladePath::Tessellation ? BladePath::Tessellation : BladePath::Compute;
  try {
    impl->init(options);
  } catch (const VulkanError& e) {
    return makeError(ErrorKind::Gpu, e.what());
  }
  return std::unique_ptr<Renderer>(new Renderer(std::move(impl)));
}

const DeviceInfo& Renderer::device() const { return impl_->ctx->info(); }
uint32_t Renderer::width() const { return impl_->targets->extent().width; }
uint32_t Renderer::height() const { return impl_->targets->extent().height; }
int Renderer::msaa() const { return impl_->msaa; }
TerrainShading Renderer::terrainShading() const { return impl_->terrainShading; }

BladePath Renderer::bladePath() const { return impl_->bladePath; }
bool Renderer::hasWindow() const { return impl_->swapchain != nullptr; }
const ValidationLog* Renderer::validationLog() const { return impl_->validationLog.get(); }

Status Renderer::setImageryLayers(uint32_t layers, ImageryCompanions companions) {
  if (layers < 1 || layers > maxImageryLayers())
    return makeError(ErrorKind::InvalidInput, "imagery layers: " + std::to_string(layers) + " is outside 1 … " +
                                                  std::to_string(maxImageryLayers()) + " for " + device().name);
  return guardGpu([&]() -> Status {
    // The imagery descriptor is rewritten: no frame in flight may still read it.
    vkCheck(vkDeviceWaitIdle(impl_->ctx->device()), "vkDeviceWaitIdle");
    impl_->terrainPass->setImageryLayers(
        layers, companions, [&](GpuImage&& old) { impl_->deletions.defer(impl_->nextFrame - 1, std::move(old)); });
    return {};
  });
}

uint32_t Renderer::imageryLayers() const { return impl_->terrainPass->imageryLayers(); }

uint32_t Renderer::maxImageryLayers() const { return impl_->ctx->properties().limits.maxImageArrayLayers; }

Result<Renderer::SimulationReadback> Renderer::readSimulation() {
  try {
    vkCheck(vkDeviceWaitIdle(impl_->ctx->device()), "vkDeviceWaitIdle");
    const Context& ctx = *impl_->ctx;
    const SimulationPass& sim = *impl_->simulation;
    GpuBuffer host = createBuffer(ctx, SimulationPass::kWindCellsBytes + SimulationPass::kFieldBytes,
                                  VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::HostReadback, "simulation read-back");
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
      const VkBufferCopy cells{0, 0, SimulationPass::kWindCellsBytes};
      const VkBufferCopy field{0, SimulationPass::kWindCellsBytes, SimulationPass::kFieldBytes};
      vkCmdCopyBuffer(cmd, sim.windCells(), host.get(), 1, &cells);
      vkCmdCopyBuffer(cmd, sim.field(), host.get(), 1, &field);
      hostReadBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    });
    SimulationReadback r;
    r.windCells.resize(SimulationPass::kWindCellsBytes / sizeof(simulation::shader::WindCellGpu));
    r.field.resize(SimulationPass::kFieldBytes / sizeof(glm::vec4));
    const auto* bytes = static_cast<const uint8_t*>(host.mapped);
    std::memcpy(r.windCells.data(), bytes, SimulationPass::kWindCellsBytes);
    std::memcpy(r.field.data(), bytes + SimulationPass::kWindCellsBytes, SimulationPass::kFieldBytes);
    return r;
  } catch (const VulkanError& e) {
    return makeError(ErrorKind::Internal, std::string("simulation read-back: ") + e.what());
  }
}

Result<std::vector<Renderer::BladeVertexReadback>> Renderer::readBladeVertices() {
  static_assert(sizeof(BladeVertexReadback) == 32, "shaders/common/blade_layout.glsl BladeVertex");
  try {
    vkCheck(vkDeviceWaitIdle(impl_->ctx->device()), "vkDeviceWaitIdle");
    const int slot = static_cast<int>((impl_->nextFrame - 1) % kFramesInFlight);
    const uint64_t count = impl_->blades->writtenVertices(slot);
    std::vector<BladeVertexReadback> out(count);
    if (count == 0) return out;
    const VkDeviceSize bytes = count * sizeof(BladeVertexReadback);
    GpuBuffer host = createBuffer(*impl_->ctx, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::HostReadback,
                                  "blade vertex read-back");
    impl_->ctx->submitAndWait([&](VkCommandBuffer cmd) {
      const VkBufferCopy region{0, 0, bytes};
      vkCmdCopyBuffer(cmd, impl_->blades->vertexBuffer(slot), host.get(), 1, &region);
      hostReadBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    });
    std::memcpy(out.data(), host.mapped, bytes);
    return out;
  } catch (const VulkanError& e) {
    return makeError(ErrorKind::Internal, std::string("blade vertex read-back: ") + e.what());
  }
}

Result<AtmosphereLuts> Renderer::readAtmosphere() {
  try {
    return impl_->atmosphere->readBack();
  } catch (const VulkanError& e) {
    return makeError(ErrorKind::Internal, std::string("atmosphere read-back: ") + e.what());
  }
}

uint64_t Renderer::simulationGpuBytes() const { return impl_->simulation->gpuBytes(); }

uint64_t Renderer::gpuBytes() const {
  return impl_->terrainPass->gpuBytes() + impl_->classify->gpuBytes() + impl_->plantPass->gpuBytes() +
         impl_->hiz->gpuBytes() + impl_->blades->gpuBytes() + impl_->simulation->gpuBytes() +
         impl_->trees->gpuBytes() + impl_->sunShadows->gpuBytes() +
         (impl_->terrainRaster ? impl_->terrainRaster->gpuBytes() : 0);
}

Status Renderer::setTreeModels(std::span<const TreeModelSet> sets) {
  return guardGpu([&]() -> Status {
    vkCheck(vkDeviceWaitIdle(impl_->ctx->device()), "vkDeviceWaitIdle");
    if (!impl_->trees->setModels(sets, impl_->treeBudgetBytes, impl_->slots[0].descriptorSet))
      return makeError(ErrorKind::InvalidInput,
                       "--tree-budget-mb " + std::to_string(impl_->treeBudgetBytes >> 20) +
                           ": too small for the tree models and their impostors (" +
                           std::to_string(impl_->trees->modelCount()) + " models)");
    return {};
  });
}

uint32_t Renderer::treePageCapacity() const { return impl_->trees->pageCapacity(); }
uint64_t Renderer::treeGpuBytes() const { return impl_->trees->gpuBytes(); }

Result<std::vector<uint8_t>> Renderer::readTreeImpostor(uint32_t model, uint32_t level) {
  if (!impl_->trees->impostors() || model >= impl_->trees->modelCount())
    return makeError(ErrorKind::InvalidInput, "no tree model " + std::to_string(model));
  if (level >= kImpostorMipLevels) return makeError(ErrorKind::InvalidInput, "no mip level " + std::to_string(level));
  return guardGpu([&]() -> Result<std::vector<uint8_t>> {
    vkCheck(vkDeviceWaitIdle(impl_->ctx->device()), "vkDeviceWaitIdle");
    return impl_->trees->impostors()->readAlbedo(model, level);
  });
}

Status Renderer::setSpeciesCatalog(const vegetation::SpeciesCatalog& catalog) {
  if (catalog.species.size() > vegetation::kMaxSpecies)
    return makeError(ErrorKind::InvalidInput, "species catalog: " + std::to_string(catalog.species.size()) +
                                                  " species, at most " + std::to_string(vegetation::kMaxSpecies));
  return guardGpu([&]() -> Status {
    vkCheck(vkDeviceWaitIdle(impl_->ctx->device()), "vkDeviceWaitIdle");  // frames in flight read the block
    impl_->classify->setCatalog(catalog);
    impl_->terrainPass->setTerrainTypes(vegetation::terrainTypesOf(catalog));
    impl_->hiz->setCatalog(catalog);
    impl_->blades->setCatalog(catalog);
    return {};
  });
}

Result<uint64_t> Renderer::submitFrame(const FrameRequest& request) {
  if (request.vegetation && request.vegetation->draw.path == BladePath::Mesh)
    return makeError(ErrorKind::Unsupported, "blade path mesh: this build has no mesh-shader blade path");
  return guardGpu([&]() -> Result<uint64_t> { return impl_->submit(request); });
}

Result<FrameResult> Renderer::waitFrame(uint64_t index) {
  FrameSlot& slot = impl_->slots[index % kFramesInFlight];
  if (!slot.submitted || slot.frameIndex != index)
    return makeError(ErrorKind::Internal, "frame " + std::to_string(index) + " is not one of the last " +
                                              std::to_string(kFramesInFlight) + " submitted");
  return guardGpu([&]() -> Result<FrameResult> { return impl_->collect(slot); });
}

Result<FrameResult> Renderer::renderFrame(const FrameRequest& request) {
  auto index = submitFrame(request);
  if (!index) return index.error();
  return waitFrame(*index);
}

}  // namespace vegstream::render
