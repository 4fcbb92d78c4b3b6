// The renderer (renderer.h): its creation from the options and the device, and the public API's
// setters and debug read-backs. Renderer::Impl owns the context, the targets, the swapchain,
// set 0's layout and pool, and two collaborators: the passes and the order a frame records them
// in (frame_passes.h) and the frame slots' life — submission, read-back, present, collect
// (frame_submitter.h).
#include "render/renderer.h"

#include <cstring>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include "render/atmosphere_pass.h"
#include "render/blade_pass.h"
#include "render/frame_passes.h"
#include "render/frame_slot.h"
#include "render/frame_submitter.h"
#include "render/render_targets.h"
#include "render/simulation_pass.h"
#include "render/sun_shadow_pass.h"
#include "render/swapchain.h"
#include "render/terrain_pass.h"
#include "render/tree_impostors.h"
#include "render/tree_pass.h"
#include "render/vk_check.h"

namespace vegstream::render {

struct Renderer::Impl {
  std::unique_ptr<Context> ctx;
  std::shared_ptr<ValidationLog> validationLog;
  std::unique_ptr<RenderTargets> targets;
  std::unique_ptr<Swapchain> swapchain;
  DescriptorSetLayout frameLayout;
  DescriptorPool descriptorPool;
  std::unique_ptr<FramePasses> passes;
  std::unique_ptr<FrameSubmitter> frames;  // first to go: retires what the frames deferred
  uint64_t treeBudgetBytes = 0;
  streaming::DiskTileCache* impostorCache = nullptr;
  BladePath bladePath = BladePath::Compute;  // resolved: never Auto or Mesh
  int msaa = 1;
  TerrainShading terrainShading = TerrainShading::Forward;

  ~Impl() {
    if (ctx) vkDeviceWaitIdle(ctx->device());
  }

  void init(const RendererOptions& options);
};

// The targets, the swapchain, set 0's layout and pool, the passes set 0 refers to, the frame
// slots with their frame sets, then the passes that draw (frame_passes.h).
void Renderer::Impl::init(const RendererOptions& options) {
  const VkExtent2D extent{options.width, options.height};
  const bool computeRaster = terrainShading == TerrainShading::Compute;
  const bool deferred = terrainShading == TerrainShading::Deferred || computeRaster;
  targets =
      std::make_unique<RenderTargets>(*ctx, extent, static_cast<VkSampleCountFlagBits>(msaa), deferred, computeRaster);
  if (options.window) swapchain = std::make_unique<Swapchain>(*ctx, options.window);
  frameLayout = createFrameSetLayout(*ctx);
  descriptorPool = createFrameSetPool(*ctx);
  passes = std::make_unique<FramePasses>(*ctx, frameLayout.get(), *targets, options, terrainShading, bladePath);
  frames = std::make_unique<FrameSubmitter>(*ctx, *targets, swapchain.get(), *passes, frameLayout.get(),
                                            descriptorPool.get());
  passes->createDrawPasses(options);
  treeBudgetBytes = options.treeBudgetBytes;
  impostorCache = options.impostorCache;
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
    impl_->passes->terrain().setImageryLayers(layers, companions,
                                              [&](GpuImage&& old) { impl_->frames->retire(std::move(old)); });
    return {};
  });
}

uint32_t Renderer::imageryLayers() const { return impl_->passes->terrain().imageryLayers(); }

uint32_t Renderer::maxImageryLayers() const { return impl_->ctx->properties().limits.maxImageArrayLayers; }

Result<Renderer::SimulationReadback> Renderer::readSimulation() {
  try {
    vkCheck(vkDeviceWaitIdle(impl_->ctx->device()), "vkDeviceWaitIdle");
    const Context& ctx = *impl_->ctx;
    const SimulationPass& sim = impl_->passes->simulation();
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
    const int slot = static_cast<int>(impl_->frames->lastFrame() % kFramesInFlight);
    const BladePass& blades = impl_->passes->blades();
    const uint64_t count = blades.writtenVertices(slot);
    std::vector<BladeVertexReadback> out(count);
    if (count == 0) return out;
    const VkDeviceSize bytes = count * sizeof(BladeVertexReadback);
    GpuBuffer host = createBuffer(*impl_->ctx, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::HostReadback,
                                  "blade vertex read-back");
    impl_->ctx->submitAndWait([&](VkCommandBuffer cmd) {
      const VkBufferCopy region{0, 0, bytes};
      vkCmdCopyBuffer(cmd, blades.vertexBuffer(slot), host.get(), 1, &region);
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
    return impl_->passes->atmosphere().readBack();
  } catch (const VulkanError& e) {
    return makeError(ErrorKind::Internal, std::string("atmosphere read-back: ") + e.what());
  }
}

uint64_t Renderer::simulationGpuBytes() const { return impl_->passes->simulation().gpuBytes(); }

uint64_t Renderer::gpuBytes() const { return impl_->passes->gpuBytes(); }

Status Renderer::setTreeModels(std::span<const TreeModelSet> sets) {
  return guardGpu([&]() -> Status {
    vkCheck(vkDeviceWaitIdle(impl_->ctx->device()), "vkDeviceWaitIdle");
    TreePass& trees = impl_->passes->trees();
    if (!trees.setModels(sets, impl_->treeBudgetBytes, impl_->frames->frameSet(0), impl_->impostorCache))
      return makeError(ErrorKind::InvalidInput, "--tree-budget-mb " + std::to_string(impl_->treeBudgetBytes >> 20) +
                                                    ": too small for the tree models and their impostors (" +
                                                    std::to_string(trees.modelCount()) + " models)");
    return {};
  });
}

uint32_t Renderer::treePageCapacity() const { return impl_->passes->trees().pageCapacity(); }

const ImpostorCacheFigures& Renderer::impostorCacheFigures() const {
  return impl_->passes->trees().impostorCacheFigures();
}
uint64_t Renderer::treeGpuBytes() const { return impl_->passes->trees().gpuBytes(); }

Result<std::vector<uint8_t>> Renderer::readTreeImpostor(uint32_t model, uint32_t level) {
  const TreePass& trees = impl_->passes->trees();
  if (!trees.impostors() || model >= trees.modelCount())
    return makeError(ErrorKind::InvalidInput, "no tree model " + std::to_string(model));
  if (level >= kImpostorMipLevels) return makeError(ErrorKind::InvalidInput, "no mip level " + std::to_string(level));
  return guardGpu([&]() -> Result<std::vector<uint8_t>> {
    vkCheck(vkDeviceWaitIdle(impl_->ctx->device()), "vkDeviceWaitIdle");
    return trees.impostors()->readAlbedo(model, level);
  });
}

Result<std::vector<uint32_t>> Renderer::readTreeList(uint32_t model, uint32_t lod) {
  const TreePass& trees = impl_->passes->trees();
  if (model >= trees.modelCount()) return makeError(ErrorKind::InvalidInput, "no tree model " + std::to_string(model));
  if (lod > 1) return makeError(ErrorKind::InvalidInput, "no tree mesh level " + std::to_string(lod));
  return guardGpu([&]() -> Result<std::vector<uint32_t>> {
    vkCheck(vkDeviceWaitIdle(impl_->ctx->device()), "vkDeviceWaitIdle");
    return trees.readList(model, lod);
  });
}

Result<std::vector<uint32_t>> Renderer::readSunShadowMap() {
  return guardGpu([&]() -> Result<std::vector<uint32_t>> {
    vkCheck(vkDeviceWaitIdle(impl_->ctx->device()), "vkDeviceWaitIdle");
    return impl_->passes->sunShadows().read();
  });
}

Status Renderer::setSpeciesCatalog(const vegetation::SpeciesCatalog& catalog) {
  if (catalog.species.size() > vegetation::kMaxSpecies)
    return makeError(ErrorKind::InvalidInput, "species catalog: " + std::to_string(catalog.species.size()) +
                                                  " species, at most " + std::to_string(vegetation::kMaxSpecies));
  return guardGpu([&]() -> Status {
    vkCheck(vkDeviceWaitIdle(impl_->ctx->device()), "vkDeviceWaitIdle");  // frames in flight read the block
    impl_->passes->setCatalog(catalog);
    return {};
  });
}

Result<uint64_t> Renderer::submitFrame(const FrameRequest& request) {
  if (request.vegetation && request.vegetation->draw.path == BladePath::Mesh)
    return makeError(ErrorKind::Unsupported, "blade path mesh: this build has no mesh-shader blade path");
  return guardGpu([&]() -> Result<uint64_t> { return impl_->frames->submit(request); });
}

Result<FrameResult> Renderer::waitFrame(uint64_t index) {
  if (!impl_->frames->holds(index))
    return makeError(ErrorKind::Internal, "frame " + std::to_string(index) + " is not one of the last " +
                                              std::to_string(kFramesInFlight) + " submitted");
  return guardGpu([&]() -> Result<FrameResult> { return impl_->frames->collect(index); });
}

Result<FrameResult> Renderer::renderFrame(const FrameRequest& request) {
  auto index = submitFrame(request);
  if (!index) return index.error();
  return waitFrame(*index);
}

}  // namespace vegstream::render
