// The frame slots' life (frame_submitter.h): a slot waited for, a frame recorded and
// submitted, its read-backs and present blit, and what it yields once done.
#include "render/frame_submitter.h"

#include <algorithm>
#include <string>

#include <glm/matrix.hpp>

#include "core/stopwatch.h"
#include "render/descriptors.h"
#include "render/frame_passes.h"
#include "render/frame_uniforms.h"
#include "render/render_targets.h"
#include "render/swapchain.h"
#include "render/vk_check.h"

namespace vegstream::render {

FrameSubmitter::FrameSubmitter(const Context& ctx, const RenderTargets& targets, Swapchain* swapchain,
                               FramePasses& passes, VkDescriptorSetLayout frameLayout, VkDescriptorPool pool)
    : ctx_(ctx), targets_(targets), swapchain_(swapchain), passes_(passes) {
  const VkDeviceSize pixels = VkDeviceSize{targets.extent().width} * targets.extent().height;
  for (int i = 0; i < kFramesInFlight; ++i) {
    FrameSlot& s = slots_[static_cast<size_t>(i)];
    createFrameSlot(ctx, s, i, pixels);
    const std::string tag = " (slot " + std::to_string(i) + ")";
    s.descriptorSet = allocateDescriptorSet(ctx, pool, frameLayout, "frame uniforms set" + tag);
    writeUniformBuffer(ctx, s.descriptorSet, s.uniforms.get(), sizeof(FrameUniforms));
    passes.writeFrameSet(s.descriptorSet, i, /*shadowPass=*/false);
    // The shadow pass's own: binding 4 a placeholder map.
    s.shadowPassSet = allocateDescriptorSet(ctx, pool, frameLayout, "shadow pass frame set" + tag);
    writeUniformBuffer(ctx, s.shadowPassSet, s.uniforms.get(), sizeof(FrameUniforms));
    passes.writeFrameSet(s.shadowPassSet, i, /*shadowPass=*/true);
  }
}

FrameSubmitter::~FrameSubmitter() { deletions_.collectAll(); }

void FrameSubmitter::waitSlot(FrameSlot& slot) {
  if (!slot.submitted) return;
  VkFence fence = slot.fence.get();
  vkCheck(vkWaitForFences(ctx_.device(), 1, &fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
  // A fence's signal covers every command submitted before it on the queue, so frame F done
  // means every frame up to F is done, whichever slot was waited for first (waitFrame may take
  // the frames in flight in any order): the deletion queue retires by that number.
  completedFrame_ = std::max(completedFrame_, slot.frameIndex);
  deletions_.collect(completedFrame_);
}

uint64_t FrameSubmitter::submit(const FrameRequest& request) {
  Stopwatch watch;
  const uint64_t index = nextFrame_++;
  FrameSlot& slot = slots_[index % kFramesInFlight];
  waitSlot(slot);
  VkFence fence = slot.fence.get();
  vkCheck(vkResetFences(ctx_.device(), 1, &fence), "vkResetFences");
  passes_.prepareFrame(slot, request, index);

  std::optional<uint32_t> imageIndex;
  if (request.present && swapchain_) imageIndex = swapchain_->acquire(slot.imageAcquired.get());

  vkCheck(vkResetCommandPool(ctx_.device(), slot.pool.get(), 0), "vkResetCommandPool");
  VkCommandBuffer cmd = slot.cmd;
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  vkCheck(vkBeginCommandBuffer(cmd, &bi), "vkBeginCommandBuffer");
  slot.timer->begin(cmd);
  planReadbacks(slot, request);
  passes_.record(cmd, slot, index, request, deletions_);
  recordReadback(cmd, slot, slot.readColor, slot.readDepth);
  if (slot.readAov) recordAovReadback(cmd, slot);
  if (imageIndex) recordPresent(cmd, *imageIndex);
  slot.timer->end(cmd);
  vkCheck(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");

  queueSubmit(slot, imageIndex);
  if (imageIndex) swapchain_->present(*imageIndex, swapchain_->renderDone(*imageIndex));

  slot.frameIndex = index;
  slot.submitted = true;
  slot.cpuRecordMs = watch.elapsedMs();
  return index;
}

// What the frame reads back into its slot (the slot's last frame is done: waitSlot).
void FrameSubmitter::planReadbacks(FrameSlot& slot, const FrameRequest& request) {
  const VkExtent2D extent = targets_.extent();
  slot.readAov = request.aov;
  if (request.aov && !slot.aovReadback.get())  // one packed-float texel (4 bytes) a pixel
    slot.aovReadback = createBuffer(ctx_, size_t{extent.width} * extent.height * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                    MemoryUse::HostReadback, "AOV read-back");
  slot.readColor = request.readbackColor && !request.aov;
  slot.readDepth = request.readbackDepth || request.aov;  // the passes resolve the depth only for it
  if (request.aov)
    slot.aovInverseProjection = glm::inverse(projection(request.camera, double(extent.width) / double(extent.height)));
}

bool FrameSubmitter::holds(uint64_t index) const {
  const FrameSlot& slot = slots_[index % kFramesInFlight];
  return slot.submitted && slot.frameIndex == index;
}

void FrameSubmitter::queueSubmit(FrameSlot& slot, std::optional<uint32_t> imageIndex) {
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
    signalInfo.semaphore = swapchain_->renderDone(*imageIndex);
    signalInfo.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    si.waitSemaphoreInfoCount = 1;
    si.pWaitSemaphoreInfos = &waitInfo;
    si.signalSemaphoreInfoCount = 1;
    si.pSignalSemaphoreInfos = &signalInfo;
  }
  vkCheck(vkQueueSubmit2(ctx_.queue(), 1, &si, fence), "vkQueueSubmit2");
}

void FrameSubmitter::recordReadback(VkCommandBuffer cmd, FrameSlot& slot, bool readColor, bool readDepth) const {
  const VkExtent2D extent = targets_.extent();
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
    copy(targets_.display(), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
         VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, slot.colorReadback);
  if (readDepth)
    copy(targets_.depth(), VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
         VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
         VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, slot.depthReadback);
}

void FrameSubmitter::recordAovReadback(VkCommandBuffer cmd, FrameSlot& slot) const {
  const VkExtent2D extent = targets_.extent();
  const GpuImage& hdr = targets_.color();
  constexpr VkPipelineStageFlags2 kCompute = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
  transitionImage(cmd, hdr.get(), hdr.aspect, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, kCompute,
                  VK_ACCESS_2_SHADER_STORAGE_READ_BIT, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
  VkBufferImageCopy region{};
  region.imageSubresource = {hdr.aspect, 0, 0, 1};
  region.imageExtent = {extent.width, extent.height, 1};
  vkCmdCopyImageToBuffer(cmd, hdr.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, slot.aovReadback.get(), 1, &region);
  hostReadBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  transitionImage(cmd, hdr.get(), hdr.aspect, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL,
                  VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT, kCompute,
                  VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
}

void FrameSubmitter::recordPresent(VkCommandBuffer cmd, uint32_t imageIndex) const {
  const GpuImage& src = targets_.display();
  const VkImage dst = swapchain_->image(imageIndex);
  transitionImage(cmd, src.get(), src.aspect, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                  VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                  VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
  transitionImage(cmd, dst, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                  VK_PIPELINE_STAGE_2_BLIT_BIT, 0, VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  const VkExtent2D s = targets_.extent(), d = swapchain_->extent();
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
FrameResult FrameSubmitter::collect(uint64_t index) {
  FrameSlot& slot = slots_[index % kFramesInFlight];
  waitSlot(slot);
  FrameResult r;
  r.frameIndex = slot.frameIndex;
  r.cpuRecordMs = slot.cpuRecordMs;
  r.terrainTriangles = slot.terrainTriangles;
  passes_.readFigures(slot, r);
  r.gpu = slot.timer->read();
  readSlotImages(slot, targets_.extent(), r);
  return r;
}

}  // namespace vegstream::render
