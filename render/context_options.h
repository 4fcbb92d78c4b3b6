#pragma once
// How the Vulkan context is made (device choice, validation, extensions) and which devices
// exist — plain data, so code above render/ picks a device without seeing a Vulkan type.

#include <memory>
#include <string>
#include <vector>

#include "core/log.h"
#include "core/result.h"
#include "render/device_info.h"
#include "render/validation.h"

namespace vegstream::render {

struct ContextOptions {
  bool validate = false;                         // VK_LAYER_KHRONOS_validation + debug messenger
  std::string deviceName;                        // empty: pick the best device
  std::vector<std::string> instanceExtensions;   // e.g. what GLFW needs for a window surface
  bool wantSwapchain = false;                    // enable VK_KHR_swapchain on the device
  std::shared_ptr<ValidationLog> validationLog;  // where validation messages go (may be null)
  Logger logger;                                 // may be null
};

// Every device the driver offers, in enumeration order. Does not create a logical device.
Result<std::vector<DeviceInfo>> listDevices();

}  // namespace vegstream::render
