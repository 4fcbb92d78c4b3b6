#pragma once
// Private to render/: the frame slots' life (render/frame_slot.h: kFramesInFlight of them) — a
// slot waited for, its command buffer begun, the frame's passes recorded (render/frame_passes.h),
// its read-backs and present blit, the queue submission and present; then, once its fence has
// signalled, what the frame yields (collect). Owns the slots, the frame counters and the deletion
// queue that retires what a frame replaced once that frame has completed.
//
// Contract: frames are numbered from 1 in submission order; collect takes any of the last
// kFramesInFlight submitted, in any order. A fence covers every command submitted before it, so
// the deletion queue retires by the highest frame known done. Every Vulkan failure throws
// VulkanError (render/vk_check.h).

#include <array>
#include <cstdint>
#include <optional>

#include "render/deletion_queue.h"
#include "render/frame_slot.h"

namespace vegstream::render {

class FramePasses;
class RenderTargets;
class Swapchain;

class FrameSubmitter {
 public:
  // Every slot's resources for the targets' size and its two frame sets from `pool` (the second
  // the shadow pass's). ctx, targets, swapchain (null: no window) and passes must outlive it.
  FrameSubmitter(const Context& ctx, const RenderTargets& targets, Swapchain* swapchain, FramePasses& passes,
                 VkDescriptorSetLayout frameLayout, VkDescriptorPool pool);
  ~FrameSubmitter();  // after vkDeviceWaitIdle: retires everything deferred
  FrameSubmitter(const FrameSubmitter&) = delete;
  FrameSubmitter& operator=(const FrameSubmitter&) = delete;

  // Records and submits one frame; returns its index. Waits only for the frame that last used
  // the slot (index − kFramesInFlight), when it has not been waited for.
  uint64_t submit(const FrameRequest& request);
  // Whether frame `index` is one of the last kFramesInFlight submitted (collect takes it).
  bool holds(uint64_t index) const;
  // Waits for frame `index` (holds(index)) and returns its figures and read-backs.
  FrameResult collect(uint64_t index);

  uint64_t lastFrame() const { return nextFrame_ - 1; }  // 0 before the first
  // Keeps `owner` alive until the last frame submitted so far has completed.
  template <typename T>
  void retire(T&& owner) {
    deletions_.defer(lastFrame(), std::forward<T>(owner));
  }
  VkDescriptorSet frameSet(int slot) const { return slots_[static_cast<size_t>(slot)].descriptorSet; }

 private:
  void waitSlot(FrameSlot& slot);
  void planReadbacks(FrameSlot& slot, const FrameRequest& request);
  void queueSubmit(FrameSlot& slot, std::optional<uint32_t> imageIndex);
  void recordReadback(VkCommandBuffer cmd, FrameSlot& slot, bool color, bool depth) const;
  // An AOV frame's resolved float target (left in the general layout by the tone map) → aovReadback.
  void recordAovReadback(VkCommandBuffer cmd, FrameSlot& slot) const;
  void recordPresent(VkCommandBuffer cmd, uint32_t imageIndex) const;

  const Context& ctx_;
  const RenderTargets& targets_;
  Swapchain* swapchain_;
  FramePasses& passes_;
  std::array<FrameSlot, kFramesInFlight> slots_;
  DeletionQueue deletions_;
  uint64_t nextFrame_ = 1;       // frame indices start at 1; 0 means "none"
  uint64_t completedFrame_ = 0;  // highest frame known finished on the GPU
};

}  // namespace vegstream::render
