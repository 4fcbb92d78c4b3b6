#pragma once
// The Vulkan instance, the chosen physical device, the logical device and its one graphics
// queue. Device choice: the device whose name contains ContextOptions::deviceName
// (case-insensitive), otherwise the best by type — discrete, integrated, virtual GPU, then a
// CPU rasteriser such as Mesa lavapipe.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "core/log.h"
#include "core/result.h"
#include "render/context_options.h"
#include "render/device_info.h"
#include "render/handle.h"
#include "render/validation.h"

namespace vegstream::render {

class Context {
 public:
  static Result<std::unique_ptr<Context>> create(const ContextOptions& options);
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  VkInstance instance() const { return instance_; }
  VkPhysicalDevice physicalDevice() const { return physical_; }
  VkDevice device() const { return device_; }
  VkQueue queue() const { return queue_; }
  uint32_t queueFamily() const { return queueFamily_; }
  const DeviceInfo& info() const { return info_; }
  const VkPhysicalDeviceProperties& properties() const { return properties_; }
  bool validationEnabled() const { return messenger_ != VK_NULL_HANDLE; }
  const Logger& logger() const { return logger_; }

  // Index of a memory type with `required` properties among `typeBits`; throws if none.
  uint32_t findMemoryType(uint32_t typeBits, VkMemoryPropertyFlags required) const;

  // Gives the object a name in validation messages and GPU debuggers (VK_EXT_debug_utils).
  void setName(VkObjectType type, uint64_t handle, const std::string& name) const;
  template <typename H>
  void setName(VkObjectType type, H handle, const std::string& name) const {
    setName(type, reinterpret_cast<uint64_t>(handle), name);
  }

  // Records commands with `record`, submits them and waits (uploads, one-off copies).
  void submitAndWait(const std::function<void(VkCommandBuffer)>& record) const;

 private:
  Context() = default;
  void init(const ContextOptions& options);
  void createInstance(const ContextOptions& options);
  void choosePhysicalDevice(const ContextOptions& options);
  void createDevice(const ContextOptions& options);

  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  uint32_t queueFamily_ = 0;
  VkPhysicalDeviceProperties properties_{};
  VkPhysicalDeviceMemoryProperties memory_{};
  DeviceInfo info_;
  std::shared_ptr<ValidationLog> validationLog_;
  Logger logger_;
  PFN_vkSetDebugUtilsObjectNameEXT setObjectName_ = nullptr;
  CommandPool uploadPool_;
};

}  // namespace vegstream::render
