#pragma once
// Move-only owners of Vulkan objects. An owner destroys its object when it dies, so code that
// must wait for the GPU hands the owner to a DeletionQueue (deletion_queue.h) instead of
// letting it go out of scope while a frame in flight may still use it.

#include <utility>

#include <vulkan/vulkan.h>

namespace vegstream::render {

template <typename Handle, void (*Destroy)(VkDevice, Handle, const VkAllocationCallbacks*)>
class DeviceObject {
 public:
  DeviceObject() = default;
  DeviceObject(VkDevice device, Handle handle) : device_(device), handle_(handle) {}
  ~DeviceObject() { reset(); }
  DeviceObject(const DeviceObject&) = delete;
  DeviceObject& operator=(const DeviceObject&) = delete;
  DeviceObject(DeviceObject&& o) noexcept
      : device_(std::exchange(o.device_, VK_NULL_HANDLE)), handle_(std::exchange(o.handle_, VK_NULL_HANDLE)) {}
  DeviceObject& operator=(DeviceObject&& o) noexcept {
    if (this != &o) {
      reset();
      device_ = std::exchange(o.device_, VK_NULL_HANDLE);
      handle_ = std::exchange(o.handle_, VK_NULL_HANDLE);
    }
    return *this;
  }

  Handle get() const { return handle_; }
  explicit operator bool() const { return handle_ != VK_NULL_HANDLE; }
  void reset() {
    if (handle_ != VK_NULL_HANDLE) Destroy(device_, handle_, nullptr);
    handle_ = VK_NULL_HANDLE;
  }

 private:
  VkDevice device_ = VK_NULL_HANDLE;
  Handle handle_ = VK_NULL_HANDLE;
};

using Buffer = DeviceObject<VkBuffer, vkDestroyBuffer>;
using Image = DeviceObject<VkImage, vkDestroyImage>;
using ImageView = DeviceObject<VkImageView, vkDestroyImageView>;
using DeviceMemory = DeviceObject<VkDeviceMemory, vkFreeMemory>;
using ShaderModule = DeviceObject<VkShaderModule, vkDestroyShaderModule>;
using PipelineLayout = DeviceObject<VkPipelineLayout, vkDestroyPipelineLayout>;
using Pipeline = DeviceObject<VkPipeline, vkDestroyPipeline>;
using DescriptorSetLayout = DeviceObject<VkDescriptorSetLayout, vkDestroyDescriptorSetLayout>;
using DescriptorPool = DeviceObject<VkDescriptorPool, vkDestroyDescriptorPool>;
using CommandPool = DeviceObject<VkCommandPool, vkDestroyCommandPool>;
using Fence = DeviceObject<VkFence, vkDestroyFence>;
using Semaphore = DeviceObject<VkSemaphore, vkDestroySemaphore>;
using QueryPool = DeviceObject<VkQueryPool, vkDestroyQueryPool>;
using Sampler = DeviceObject<VkSampler, vkDestroySampler>;

}  // namespace vegstream::render
