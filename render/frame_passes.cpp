// What one frame records (Renderer::Impl, render/renderer_impl.h): the passes in order,
// read-back, present and the queue submission; and what it yields once done (collect).
#include <cassert>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include "render/renderer_impl.h"

namespace vegstream::render {

// The tone map's settings for a frame: the flat-colour coverage style and an AOV frame pass
// their colours through (identity), a fixed --exposure is fixed, otherwise automatic (smoothed in the window).
namespace {
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

// The frame's passes, in order: imagery uploads; the terrain's geometry (front to back) — then
// deferred: the visibility scope and the shade (compute, sky included), or forward: scope 1
// with sky and terrain; with plants: the Hi-Z build from the terrain's depth and the classify
// pass (compute, culling the seed triangles the terrain hides), the compute blade expansion,
// then the plants' scope (loading colour and depth, resolving); the HUD over the resolved image.
void Renderer::Impl::recordPasses(VkCommandBuffer cmd, FrameSlot& slot, uint64_t index, const FrameRequest& request) {
  const auto retireBuffer = [&](GpuBuffer&& old) { deletions.defer(index, std::move(old)); };
  const int slotIndex = static_cast<int>(index % kFramesInFlight);
  terrainPass->recordUploads(cmd, slotIndex, request.imageryUploads, retireBuffer);
  slot.vegetation.reset();
  slot.bladesExpanded = false;
  slot.treesDrawn = false;
  const VegetationRequest* plants = request.vegetation;
  const TreeRequest* treeRequest = request.trees && trees->modelCount() > 0 ? request.trees : nullptr;
  if (request.simulation) {  // before anything reads the wind cells or the interaction field
    slot.timer->beginPass(cmd, "simulation");
    simulation->record(cmd, slot.descriptorSet, *request.simulation);
    slot.timer->endPass(cmd);
  }

  slot.timer->beginPass(cmd, "atmosphere");  // the LUTs and the light every later pass reads
  atmosphere->record(cmd, request.cameraHeightMsl, glm::vec3(glm::normalize(request.lighting.sunDirection)));
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
    hiz->recordBuild(cmd);
    slot.timer->endPass(cmd);
  }
  if (treeRequest) {  // trees in their own scope, before the plants: they hide much of them
    slot.timer->beginPass(cmd, "trees");
    targets->beginRendering(cmd, next, /*resolve=*/plants == nullptr, slot.readDepth);
    trees->recordDraw(cmd, slotIndex, slot.descriptorSet);
    vkCmdEndRendering(cmd);
    slot.timer->endPass(cmd);
    next = RenderTargets::Load::Keep;
  }
  if (plants) {
    recordPlants(cmd, slot, slotIndex, *plants, next, retireBuffer);
  } else if ((terrainShade || terrainRaster) && !treeRequest) {  // no plants: one empty scope resolves the shaded targets
    targets->beginRendering(cmd, next, /*resolve=*/true, slot.readDepth);
    vkCmdEndRendering(cmd);
  }
  if (terrainRaster) terrainRaster->recordEndOfFrame(cmd);
  slot.timer->beginPass(cmd, "tonemap");
  tonemap->record(cmd, slotIndex, toneSettings(request), *targets);
  slot.timer->endPass(cmd);
  if (request.overlay) {  // over the resolved image, so read-back and present include it
    slot.timer->beginPass(cmd, "hud");
    hudPass->record(
        cmd, static_cast<int>(index % kFramesInFlight), *request.overlay, targets->display(),
        [&](GpuBuffer&& old) { deletions.defer(index, std::move(old)); },
        [&](GpuImage&& old) { deletions.defer(index, std::move(old)); });
    slot.timer->endPass(cmd);
  }
}

// The trees classified (compute) for this frame's view and its shadow cascades.
void Renderer::Impl::recordTreeClassify(VkCommandBuffer cmd, FrameSlot& slot, int slotIndex, const FrameRequest& request,
                                        const TreeRequest& treeRequest, const ClassifyPass::RetireBuffer& retire) {
  slot.timer->beginPass(cmd, "tree classify");
  const VkExtent2D e = targets->extent();
  const glm::dmat4 viewProj =
      projection(request.camera, double(e.width) / double(e.height)) * viewRotation(request.camera);
  trees->recordClassify(cmd, slotIndex, slot.descriptorSet, treeRequest, viewProj,
                        treeLodScale(e.height, request.camera.verticalFovDeg), slot.shadows ? 40.0f : 0.0f, retire);
  slot.timer->endPass(cmd);
  slot.treesDrawn = true;
}

// The trees cast into the sun's shadow map's cascades (slot.shadows).
void Renderer::Impl::recordShadows(VkCommandBuffer cmd, FrameSlot& slot, int slotIndex) {
  slot.timer->beginPass(cmd, "shadow");
  sunShadows->record(cmd, *slot.shadows, [&](VkCommandBuffer c, int cascade, const glm::mat4& m) {
    trees->recordShadow(c, slotIndex, slot.shadowPassSet, cascade, m);
  });
  slot.timer->endPass(cmd);
}

// The terrain: rasterised and shaded in compute, deferred (ids, then shaded in compute, sky
// included) or forward (sky and terrain in one scope, resolved when lastScope). Returns how the
// next scope starts.
RenderTargets::Load Renderer::Impl::recordTerrain(VkCommandBuffer cmd, FrameSlot& slot, int slotIndex,
                                                  const FrameRequest& request, bool lastScope,
                                                  const ClassifyPass::RetireBuffer& retire) {
  slot.terrainTriangles =
      terrainPass->prepare(cmd, slotIndex, request.camera.position, request.terrain, retire);
  if (terrainRaster) {  // rasterised and shaded in compute: no graphics work for the terrain
    slot.timer->beginPass(cmd, "terrain");
    terrainRaster->record(cmd, slotIndex, slot.descriptorSet, *terrainPass, *targets, slot.terrainTriangles,
                          retire, [&] {
                            slot.timer->endPass(cmd);
                            slot.timer->beginPass(cmd, "terrain shade");
                          });
    slot.timer->endPass(cmd);
    // Its depth samples into the depth attachment: the trees and plants are depth-tested against
    // the terrain by the hardware, hidden fragments rejected before they are shaded (on the H200,
    // benchmark-30s: trees pass p50 1.23 → 0.82 ms against testing each fragment against the
    // samples in its shader; this pass costs 0.68 ms, the clear it replaces 0.59).
    slot.timer->beginPass(cmd, "terrain depth");
    terrainRaster->recordDepthAttachment(cmd, slot.descriptorSet, *targets);
    slot.timer->endPass(cmd);
    return RenderTargets::Load::Shaded;
  } else if (terrainShade) {  // deferred: triangle ids, then every pixel shaded in compute (sky included)
    slot.timer->beginPass(cmd, "terrain");
    targets->beginVisibility(cmd);
    terrainPass->recordVisibility(cmd, slotIndex, slot.descriptorSet);
    vkCmdEndRendering(cmd);
    slot.timer->endPass(cmd);
    slot.timer->beginPass(cmd, "terrain shade");
    targets->visibilityToShade(cmd);
    terrainShade->record(cmd, slotIndex, slot.descriptorSet, *terrainPass, *targets);
    slot.timer->endPass(cmd);
    return RenderTargets::Load::Shaded;
  } else {
    targets->beginRendering(cmd, RenderTargets::Load::Clear, /*resolve=*/lastScope, slot.readDepth);
    slot.timer->beginPass(cmd, "sky");
    sky->record(cmd, slot.descriptorSet);
    slot.timer->endPass(cmd);
    slot.timer->beginPass(cmd, "terrain");
    terrainPass->recordForward(cmd, slotIndex, slot.descriptorSet);
    slot.timer->endPass(cmd);
    vkCmdEndRendering(cmd);
  }
  return RenderTargets::Load::Keep;
}

// After the terrain's scope: Hi-Z build + classify (culling hidden seed triangles when asked),
// then the plants in a second scope that loads the terrain's colour and depth and resolves.
void Renderer::Impl::recordPlants(VkCommandBuffer cmd, FrameSlot& slot, int slotIndex, const VegetationRequest& plants,
                                  RenderTargets::Load load, const ClassifyPass::RetireBuffer& retire) {
  const uint32_t patchMask = plants.style == PlantStyle::Plants ? PlantPass::patchMask(*classify) : 0u;
  slot.timer->beginPass(cmd, "classify");
  classify->setFades(plants.draw.fades);
  ClassifyPass::CullHook cull;
  if (plants.occlusionCulling && !plants.triangles.empty()) {
    if (!slot.hizEarly) hiz->recordBuild(cmd);
    cull = [&](VkCommandBuffer c, VkBuffer triangles, VkBuffer visible, uint32_t count) {
      hiz->recordCull(c, slotIndex, slot.descriptorSet, triangles, visible, count, plants.clusterSize,
                      plants.draw.shadows && plants.style == PlantStyle::Plants);
    };
  }
  slot.vegetation = classify->record(cmd, slotIndex, plants.triangles, plants.clusterSize,
                                     terrainPass->imageryBytesView(), terrainPass->companionView(), terrainPass->companions().flags(),
                                     PlantMarkerPass::verticesPerGroup(plants.clusterSize), patchMask, retire, cull,
                                     plants.canopy);
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

  targets->beginRendering(cmd, load, /*resolve=*/true, slot.readDepth);
  if (plants.style != PlantStyle::Hidden) {
    slot.timer->beginPass(cmd, "plants");
    if (patchMask != 0 && slot.bladesExpanded)
      blades->recordDraw(cmd, slotIndex, slot.descriptorSet);
    else if (patchMask != 0)
      plantPass->record(cmd, slotIndex, slot.descriptorSet, *classify, terrainPass->imageryView(), plants.draw);
    // Tree species are not plants (render/tree_pass.h draws them, classify rejects them as bare):
    // `--plant-style markers` draws every other species' marker (patchMask is 0 then).
    if (plants.style == PlantStyle::Markers)
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
    copy(targets->display(), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
         VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, slot.colorReadback);
  if (readDepth)
    copy(targets->depth(), VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
         VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
         VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, slot.depthReadback);
}

void Renderer::Impl::recordAovReadback(VkCommandBuffer cmd, FrameSlot& slot) const {
  const VkExtent2D extent = targets->extent();
  const GpuImage& hdr = targets->color();
  constexpr VkPipelineStageFlags2 kCompute = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
  transitionImage(cmd, hdr.get(), hdr.aspect, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, kCompute,
                  VK_ACCESS_2_SHADER_STORAGE_READ_BIT, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
  VkBufferImageCopy region{};
  region.imageSubresource = {hdr.aspect, 0, 0, 1};
  region.imageExtent = {extent.width, extent.height, 1};
  vkCmdCopyImageToBuffer(cmd, hdr.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, slot.aovReadback.get(), 1, &region);
  hostReadBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  transitionImage(cmd, hdr.get(), hdr.aspect, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL,
                  VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT, kCompute, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
}

void Renderer::Impl::recordPresent(VkCommandBuffer cmd, uint32_t imageIndex) const {
  const GpuImage& src = targets->display();
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

// The frame's figures and read-back images, once its slot's fence has signalled.
FrameResult Renderer::Impl::collect(FrameSlot& slot) {
  waitSlot(slot);
  FrameResult r;
  r.frameIndex = slot.frameIndex;
  r.cpuRecordMs = slot.cpuRecordMs;
  r.terrainTriangles = slot.terrainTriangles;
  r.terrainRasterised = terrainRaster != nullptr;
  if (terrainRaster) {
    const TerrainRasterFigures f = terrainRaster->figures(static_cast<int>(slot.frameIndex % kFramesInFlight));
    r.terrainRasterTriangles = f.rasterTriangles;
    r.terrainTileEntries = f.tileEntries;
    r.terrainTileEntriesDropped = f.tileEntriesDropped;
    r.terrainDepthEdgeTiles = f.depthEdgeTiles;
  }
  if (slot.vegetation) {
    classify->readFigures(static_cast<int>(slot.frameIndex % kFramesInFlight), *slot.vegetation);
    if (slot.vegetation->occlusionCulling && slot.vegetation->seedTriangles > 0)  // the test ran
      hiz->readFigures(static_cast<int>(slot.frameIndex % kFramesInFlight), *slot.vegetation);
    if (slot.bladesExpanded) blades->readFigures(static_cast<int>(slot.frameIndex % kFramesInFlight), *slot.vegetation);
    r.vegetation = slot.vegetation;
  }
  if (slot.treesDrawn) r.trees = trees->figures(static_cast<int>(slot.frameIndex % kFramesInFlight));
  r.exposureEv = tonemap->exposureEv(static_cast<int>(slot.frameIndex % kFramesInFlight));
  r.gpu = slot.timer->read();
  readSlotImages(slot, targets->extent(), r);
  return r;
}

}  // namespace vegstream::render
