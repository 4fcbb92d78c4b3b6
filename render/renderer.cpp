#include "render/renderer.h"

#include <algorithm>
#include <array>
#include <cstring>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include "core/stopwatch.h"
#include "render/blade_pass.h"
#include "render/deletion_queue.h"
#include "render/descriptors.h"
#include "render/frame_slots.h"
#include "render/frame_uniforms.h"
#include "render/gpu_timer.h"
#include "render/hiz_pass.h"
#include "render/hud_pass.h"
#include "render/render_targets.h"
#include "render/classify_pass.h"
#include "render/plant_marker_pass.h"
#include "render/plant_pass.h"
#include "render/sky_pass.h"
#include "render/swapchain.h"
#include "render/terrain_detail.h"
#include "render/terrain_pass.h"
#include "render/terrain_shade_pass.h"
#include "render/vk_check.h"

namespace vegstream::render {

namespace {
// Every per-slot resource follows the one constant (render/frame_slots.h).
static_assert(HudPass::kSlots == kFramesInFlight, "one HUD buffer set per frame slot");
static_assert(TerrainPass::kSlots == kFramesInFlight, "one terrain buffer set per frame slot");
static_assert(ClassifyPass::kSlots == kFramesInFlight, "one classify (and plant) buffer set per frame slot");
constexpr int kMaxPasses = 8;
constexpr int kBladeTableSegments = 16;  // the solved shapes' resolution; blades draw ≤ 16 segments

// Everything one frame in flight owns.
struct FrameSlot {
  CommandPool pool;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  Fence fence;
  Semaphore imageAcquired;
  GpuBuffer uniforms;
  VkDescriptorSet descriptorSet = VK_NULL_HANDLE;
  std::unique_ptr<GpuTimer> timer;
  GpuBuffer colorReadback, depthReadback;
  // What was submitted last in this slot.
  uint64_t frameIndex = 0;
  bool submitted = false;
  bool readColor = false, readDepth = false;
  double cpuRecordMs = 0.0;
  uint64_t terrainTriangles = 0;
  std::optional<VegetationFigures> vegetation;
  bool bladesExpanded = false;  // the compute blade path drew this frame's plants
};

VkSampleCountFlagBits toSampleBits(int samples) { return static_cast<VkSampleCountFlagBits>(samples); }
}  // namespace

struct Renderer::Impl {
  std::unique_ptr<Context> ctx;
  std::shared_ptr<ValidationLog> validationLog;
  std::unique_ptr<RenderTargets> targets;
  std::unique_ptr<Swapchain> swapchain;
  DescriptorSetLayout frameLayout;
  DescriptorPool descriptorPool;
  std::unique_ptr<SkyPass> sky;
  std::unique_ptr<TerrainPass> terrainPass;
  std::unique_ptr<TerrainShadePass> terrainShade;  // deferred terrain shading only
  std::unique_ptr<HudPass> hudPass;
  std::unique_ptr<ClassifyPass> classify;
  std::unique_ptr<HizPass> hiz;
  std::unique_ptr<PlantMarkerPass> markers;
  std::unique_ptr<PlantPass> plantPass;
  std::unique_ptr<BladePass> blades;
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
  void waitSlot(FrameSlot& slot);
  uint64_t submit(const FrameRequest& request);
  void recordPasses(VkCommandBuffer cmd, FrameSlot& slot, uint64_t index, const FrameRequest& request);
  void recordPlants(VkCommandBuffer cmd, FrameSlot& slot, int slotIndex, const VegetationRequest& plants,
                    RenderTargets::Load load, const ClassifyPass::RetireBuffer& retire);
  void queueSubmit(FrameSlot& slot, std::optional<uint32_t> imageIndex);
  void recordReadback(VkCommandBuffer cmd, FrameSlot& slot, bool color, bool depth) const;
  void recordPresent(VkCommandBuffer cmd, uint32_t imageIndex) const;
  FrameResult collect(FrameSlot& slot);
  // The path a frame's plants take: the speed-of-light pipeline is a tessellation pipeline.
  BladePath pathFor(const PlantDrawOptions& draw) const {
    if (draw.speedOfLight) return BladePath::Tessellation;
    return draw.path == BladePath::Auto ? bladePath : draw.path;
  }
};

void Renderer::Impl::init(const RendererOptions& options) {
  const VkExtent2D extent{options.width, options.height};
  const bool deferred = terrainShading == TerrainShading::Deferred;
  targets = std::make_unique<RenderTargets>(*ctx, extent, toSampleBits(msaa), deferred);
  if (options.window) swapchain = std::make_unique<Swapchain>(*ctx, options.window);

  frameLayout =
      createSingleBindingLayout(*ctx, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER,
                                VK_SHADER_STAGE_ALL_GRAPHICS | VK_SHADER_STAGE_COMPUTE_BIT, "frame uniforms layout");
  descriptorPool =
      createSingleBindingPool(*ctx, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, kFramesInFlight, "frame descriptor pool");
  const VkDescriptorSetLayout layout = frameLayout.get();

  const VkDeviceSize pixels = VkDeviceSize{extent.width} * extent.height;
  for (int i = 0; i < kFramesInFlight; ++i) {
    FrameSlot& s = slots[static_cast<size_t>(i)];
    const std::string tag = " (slot " + std::to_string(i) + ")";
    VkCommandPoolCreateInfo cpci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    cpci.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
    cpci.queueFamilyIndex = ctx->queueFamily();
    VkCommandPool cp;
    vkCheck(vkCreateCommandPool(ctx->device(), &cpci, nullptr, &cp), "vkCreateCommandPool");
    s.pool = CommandPool(ctx->device(), cp);
    ctx->setName(VK_OBJECT_TYPE_COMMAND_POOL, cp, "frame command pool" + tag);
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = cp;
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    vkCheck(vkAllocateCommandBuffers(ctx->device(), &ai, &s.cmd), "vkAllocateCommandBuffers");
    ctx->setName(VK_OBJECT_TYPE_COMMAND_BUFFER, s.cmd, "frame commands" + tag);
    VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fence;
    vkCheck(vkCreateFence(ctx->device(), &fci, nullptr, &fence), "vkCreateFence");
    s.fence = Fence(ctx->device(), fence);
    ctx->setName(VK_OBJECT_TYPE_FENCE, fence, "frame fence" + tag);
    VkSemaphoreCreateInfo sci{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    VkSemaphore sem;
    vkCheck(vkCreateSemaphore(ctx->device(), &sci, nullptr, &sem), "vkCreateSemaphore");
    s.imageAcquired = Semaphore(ctx->device(), sem);
    ctx->setName(VK_OBJECT_TYPE_SEMAPHORE, sem, "image acquired" + tag);
    s.uniforms = createBuffer(*ctx, sizeof(FrameUniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, MemoryUse::HostUpload,
                              "frame uniforms" + tag);
    s.timer = std::make_unique<GpuTimer>(*ctx, kMaxPasses, "frame" + tag);
    s.colorReadback = createBuffer(*ctx, pixels * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::HostReadback,
                                   "colour read-back" + tag);
    s.depthReadback = createBuffer(*ctx, pixels * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::HostReadback,
                                   "depth read-back" + tag);

    s.descriptorSet = allocateDescriptorSet(*ctx, descriptorPool.get(), layout, "frame uniforms set" + tag);
    writeUniformBuffer(*ctx, s.descriptorSet, s.uniforms.get(), sizeof(FrameUniforms));
  }
  sky = std::make_unique<SkyPass>(*ctx, layout, toSampleBits(msaa));
  terrainPass = std::make_unique<TerrainPass>(*ctx, layout, toSampleBits(msaa), deferred);
  if (deferred) terrainShade = std::make_unique<TerrainShadePass>(*ctx, layout, *terrainPass, *targets);
  hudPass = std::make_unique<HudPass>(*ctx);
  classify = std::make_unique<ClassifyPass>(*ctx, ClassifyOptions{});
  classify->setCatalog(vegetation::defaultSpeciesCatalog());
  hiz = std::make_unique<HizPass>(*ctx, layout, *targets);
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
  blades = std::make_unique<BladePass>(*ctx, layout, toSampleBits(msaa), std::max(options.bladeMaxVertices, 6u));
  blades->setCatalog(vegetation::defaultSpeciesCatalog());
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

uint64_t Renderer::Impl::submit(const FrameRequest& request) {
  Stopwatch watch;
  const uint64_t index = nextFrame++;
  FrameSlot& slot = slots[index % kFramesInFlight];
  waitSlot(slot);
  VkFence fence = slot.fence.get();
  vkCheck(vkResetFences(ctx->device(), 1, &fence), "vkResetFences");

  const VkExtent2D extent = targets->extent();
  const FrameUniforms u = frameUniforms(request, extent.width, extent.height);
  std::memcpy(slot.uniforms.mapped, &u, sizeof(u));

  std::optional<uint32_t> imageIndex;
  if (request.present && swapchain) imageIndex = swapchain->acquire(slot.imageAcquired.get());

  vkCheck(vkResetCommandPool(ctx->device(), slot.pool.get(), 0), "vkResetCommandPool");
  VkCommandBuffer cmd = slot.cmd;
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  vkCheck(vkBeginCommandBuffer(cmd, &bi), "vkBeginCommandBuffer");
  slot.timer->begin(cmd);
  recordPasses(cmd, slot, index, request);
  recordReadback(cmd, slot, request.readbackColor, request.readbackDepth);
  if (imageIndex) recordPresent(cmd, *imageIndex);
  slot.timer->end(cmd);
  vkCheck(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");

  queueSubmit(slot, imageIndex);
  if (imageIndex) swapchain->present(*imageIndex, swapchain->renderDone(*imageIndex));

  slot.frameIndex = index;
  slot.submitted = true;
  slot.readColor = request.readbackColor;
  slot.readDepth = request.readbackDepth;
  slot.cpuRecordMs = watch.elapsedMs();
  return index;
}

// The frame's passes, in order: imagery uploads; rendering scope 1: sky and terrain; with
// plants: the Hi-Z build from the terrain's depth and the classify pass (compute, culling the
// seed triangles the terrain hides), then rendering scope 2 (loading colour and depth): the
// plants; the HUD over the resolved image. The Hi-Z build and test count in "classify".
void Renderer::Impl::recordPasses(VkCommandBuffer cmd, FrameSlot& slot, uint64_t index, const FrameRequest& request) {
  const auto retireBuffer = [&](GpuBuffer&& old) { deletions.defer(index, std::move(old)); };
  const int slotIndex = static_cast<int>(index % kFramesInFlight);
  terrainPass->recordUploads(cmd, slotIndex, request.imageryUploads, retireBuffer);
  slot.vegetation.reset();
  slot.bladesExpanded = false;
  const VegetationRequest* plants = request.vegetation;

  slot.terrainTriangles =
      terrainPass->prepare(cmd, slotIndex, request.camera.position, request.terrain, retireBuffer);
  RenderTargets::Load next = RenderTargets::Load::Keep;  // how the plants' scope starts
  if (terrainShade) {  // deferred: triangle ids, then every pixel shaded in compute (sky included)
    slot.timer->beginPass(cmd, "terrain");
    targets->beginVisibility(cmd);
    terrainPass->recordVisibility(cmd, slotIndex, slot.descriptorSet);
    vkCmdEndRendering(cmd);
    slot.timer->endPass(cmd);
    slot.timer->beginPass(cmd, "terrain shade");
    targets->visibilityToShade(cmd);
    terrainShade->record(cmd, slotIndex, slot.descriptorSet, *terrainPass, *targets);
    slot.timer->endPass(cmd);
    next = RenderTargets::Load::Shaded;
  } else {
    targets->beginRendering(cmd, RenderTargets::Load::Clear, /*resolve=*/plants == nullptr);
    slot.timer->beginPass(cmd, "sky");
    sky->record(cmd, slot.descriptorSet);
    slot.timer->endPass(cmd);
    slot.timer->beginPass(cmd, "terrain");
    terrainPass->recordForward(cmd, slotIndex, slot.descriptorSet);
    slot.timer->endPass(cmd);
    vkCmdEndRendering(cmd);
  }
  if (plants) {
    recordPlants(cmd, slot, slotIndex, *plants, next, retireBuffer);
  } else if (terrainShade) {  // no plants: one empty scope resolves the shaded targets
    targets->beginRendering(cmd, next, /*resolve=*/true);
    vkCmdEndRendering(cmd);
  }
  if (request.overlay) {  // over the resolved image, so read-back and present include it
    slot.timer->beginPass(cmd, "hud");
    hudPass->record(
        cmd, static_cast<int>(index % kFramesInFlight), *request.overlay, targets->color(),
        [&](GpuBuffer&& old) { deletions.defer(index, std::move(old)); },
        [&](GpuImage&& old) { deletions.defer(index, std::move(old)); });
    slot.timer->endPass(cmd);
  }
}

// After the terrain's scope: Hi-Z build + classify (culling hidden seed triangles when asked),
// then the plants in a second scope that loads the terrain's colour and depth and resolves.
void Renderer::Impl::recordPlants(VkCommandBuffer cmd, FrameSlot& slot, int slotIndex, const VegetationRequest& plants,
                                  RenderTargets::Load load, const ClassifyPass::RetireBuffer& retire) {
  const uint32_t patchMask = plants.style == PlantStyle::Plants ? PlantPass::patchMask(*classify) : 0u;
  slot.timer->beginPass(cmd, "classify");
  ClassifyPass::CullHook cull;
  if (plants.occlusionCulling && !plants.triangles.empty()) {
    hiz->recordBuild(cmd);
    cull = [&](VkCommandBuffer c, VkBuffer triangles, VkBuffer visible, uint32_t count) {
      hiz->recordCull(c, slotIndex, slot.descriptorSet, triangles, visible, count, plants.clusterSize,
                      plants.draw.shadows && plants.style == PlantStyle::Plants);
    };
  }
  slot.vegetation = classify->record(cmd, slotIndex, plants.triangles, plants.clusterSize,
                                     terrainPass->imageryBytesView(),
                                     PlantMarkerPass::verticesPerGroup(plants.clusterSize), patchMask, retire, cull);
  slot.vegetation->occlusionCulling = plants.occlusionCulling;  // counts stay 0 without triangles
  slot.timer->endPass(cmd);
  // The compute blade path expands the plants before their scope (render/blade_pass.h).
  slot.bladesExpanded = plants.style == PlantStyle::Plants && pathFor(plants.draw) == BladePath::Compute;
  if (slot.bladesExpanded) {
    slot.timer->beginPass(cmd, "blades");
    blades->recordExpand(cmd, slotIndex, slot.descriptorSet, *classify, *plantPass, plants.triangles,
                         plants.clusterSize, terrainPass->imageryView(), plants.draw, retire);
    slot.timer->endPass(cmd);
  }

  targets->beginRendering(cmd, load, /*resolve=*/true);
  if (plants.style != PlantStyle::Hidden) {
    slot.timer->beginPass(cmd, "plants");
    if (patchMask != 0 && slot.bladesExpanded)
      blades->recordDraw(cmd, slotIndex, slot.descriptorSet);
    else if (patchMask != 0)
      plantPass->record(cmd, slotIndex, slot.descriptorSet, *classify, terrainPass->imageryView(), plants.draw);
    markers->record(cmd, slotIndex, slot.descriptorSet, *classify, patchMask);
    slot.timer->endPass(cmd);
  }
  vkCmdEndRendering(cmd);
}

void Renderer::Impl::queueSubmit(FrameSlot& slot, std::optional<uint32_t> imageIndex) {
  VkFence fence = slot.fence.get();
  VkCommandBufferSubmitInfo cbi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
  cbi.commandBuffer = slot.cmd;
  VkSemaphoreSubmitInfo waitInfo{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
  VkSemaphoreSubmitInfo signalInfo{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
  VkSubmitInfo2 si{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
  si.commandBufferInfoCount = 1;
  si.pCommandBufferInfos = &cbi;
  if (imageIndex) {
    waitInfo.semaphore = slot.imageAcquired.get();
    waitInfo.stageMask = VK_PIPELINE_STAGE_2_BLIT_BIT;
    signalInfo.semaphore = swapchain->renderDone(*imageIndex);
    signalInfo.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    si.waitSemaphoreInfoCount = 1;
    si.pWaitSemaphoreInfos = &waitInfo;
    si.signalSemaphoreInfoCount = 1;
    si.pSignalSemaphoreInfos = &signalInfo;
  }
  vkCheck(vkQueueSubmit2(ctx->queue(), 1, &si, fence), "vkQueueSubmit2");
}

void Renderer::Impl::recordReadback(VkCommandBuffer cmd, FrameSlot& slot, bool readColor, bool readDepth) const {
  const VkExtent2D extent = targets->extent();
  auto copy = [&](const GpuImage& img, VkImageLayout layout, VkPipelineStageFlags2 stage, VkAccessFlags2 access,
                  const GpuBuffer& dst) {
    transitionImage(cmd, img.get(), img.aspect, layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, stage, access,
                    VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    VkBufferImageCopy region{};
    region.imageSubresource = {img.aspect, 0, 0, 1};
    region.imageExtent = {extent.width, extent.height, 1};
    vkCmdCopyImageToBuffer(cmd, img.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, dst.get(), 1, &region);
    hostReadBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    // Back to the layout the present blit expects.
    transitionImage(cmd, img.get(), img.aspect, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, layout,
                    VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT, stage, access);
  };
  if (readColor)
    copy(targets->color(), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
         VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, slot.colorReadback);
  if (readDepth)
    copy(targets->depth(), VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
         VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
         VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, slot.depthReadback);
}

void Renderer::Impl::recordPresent(VkCommandBuffer cmd, uint32_t imageIndex) const {
  const GpuImage& src = targets->color();
  const VkImage dst = swapchain->image(imageIndex);
  transitionImage(cmd, src.get(), src.aspect, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                  VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                  VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
  transitionImage(cmd, dst, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                  VK_PIPELINE_STAGE_2_BLIT_BIT, 0, VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  const VkExtent2D s = targets->extent(), d = swapchain->extent();
  VkImageBlit blit{};
  blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  blit.srcOffsets[1] = {static_cast<int32_t>(s.width), static_cast<int32_t>(s.height), 1};
  blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  blit.dstOffsets[1] = {static_cast<int32_t>(d.width), static_cast<int32_t>(d.height), 1};
  vkCmdBlitImage(cmd, src.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, dst, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                 &blit, VK_FILTER_LINEAR);
  transitionImage(cmd, dst, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                  VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0);
}

FrameResult Renderer::Impl::collect(FrameSlot& slot) {
  waitSlot(slot);
  FrameResult r;
  r.frameIndex = slot.frameIndex;
  r.cpuRecordMs = slot.cpuRecordMs;
  r.terrainTriangles = slot.terrainTriangles;
  if (slot.vegetation) {
    classify->readFigures(static_cast<int>(slot.frameIndex % kFramesInFlight), *slot.vegetation);
    if (slot.vegetation->occlusionCulling && slot.vegetation->seedTriangles > 0)  // the test ran
      hiz->readFigures(static_cast<int>(slot.frameIndex % kFramesInFlight), *slot.vegetation);
    if (slot.bladesExpanded) blades->readFigures(static_cast<int>(slot.frameIndex % kFramesInFlight), *slot.vegetation);
    r.vegetation = slot.vegetation;
  }
  r.gpu = slot.timer->read();
  const VkExtent2D e = targets->extent();
  const size_t pixels = size_t{e.width} * e.height;
  if (slot.readColor) {
    ColorImage img{e.width, e.height, std::vector<uint8_t>(pixels * 4)};
    std::memcpy(img.rgba.data(), slot.colorReadback.mapped, pixels * 4);
    r.color = std::move(img);
  }
  if (slot.readDepth) {
    DepthImage img{e.width, e.height, std::vector<float>(pixels)};
    std::memcpy(img.depth.data(), slot.depthReadback.mapped, pixels * 4);
    r.depth = std::move(img);
  }
  return r;
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
  const bool canDefer = info.supportsDeferredTerrain(options.msaa);
  if (options.terrainShading == TerrainShading::Deferred && !canDefer)
    return makeError(ErrorKind::InvalidInput, "--terrain-shading deferred is not possible on " + info.name +
                                                  " at --msaa " + std::to_string(options.msaa) +
                                                  ": it cannot store into a colour target of that many samples" +
                                                  " (storage images, shaderStorageImageMultisample)");
  impl->terrainShading = options.terrainShading == TerrainShading::Forward || !canDefer ? TerrainShading::Forward
                                                                                        : TerrainShading::Deferred;
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

const char* terrainShadingName(TerrainShading shading) {
  switch (shading) {
    case TerrainShading::Auto: return "auto";
    case TerrainShading::Forward: return "forward";
    case TerrainShading::Deferred: return "deferred";
  }
  return "?";
}
BladePath Renderer::bladePath() const { return impl_->bladePath; }
bool Renderer::hasWindow() const { return impl_->swapchain != nullptr; }
const ValidationLog* Renderer::validationLog() const { return impl_->validationLog.get(); }

Status Renderer::setImageryLayers(uint32_t layers) {
  if (layers < 1 || layers > maxImageryLayers())
    return makeError(ErrorKind::InvalidInput, "imagery layers: " + std::to_string(layers) + " is outside 1 … " +
                                                  std::to_string(maxImageryLayers()) + " for " + device().name);
  return guardGpu([&]() -> Status {
    // The imagery descriptor is rewritten: no frame in flight may still read it.
    vkCheck(vkDeviceWaitIdle(impl_->ctx->device()), "vkDeviceWaitIdle");
    impl_->terrainPass->setImageryLayers(
        layers, [&](GpuImage&& old) { impl_->deletions.defer(impl_->nextFrame - 1, std::move(old)); });
    return {};
  });
}

uint32_t Renderer::imageryLayers() const { return impl_->terrainPass->imageryLayers(); }

uint32_t Renderer::maxImageryLayers() const { return impl_->ctx->properties().limits.maxImageArrayLayers; }

uint64_t Renderer::gpuBytes() const {
  return impl_->terrainPass->gpuBytes() + impl_->classify->gpuBytes() + impl_->plantPass->gpuBytes() +
         impl_->hiz->gpuBytes() + impl_->blades->gpuBytes();
}

Status Renderer::setSpeciesCatalog(const vegetation::SpeciesCatalog& catalog) {
  if (catalog.species.size() > vegetation::kMaxSpecies)
    return makeError(ErrorKind::InvalidInput, "species catalog: " + std::to_string(catalog.species.size()) +
                                                  " species, at most " + std::to_string(vegetation::kMaxSpecies));
  return guardGpu([&]() -> Status {
    vkCheck(vkDeviceWaitIdle(impl_->ctx->device()), "vkDeviceWaitIdle");  // frames in flight read the block
    impl_->classify->setCatalog(catalog);
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
