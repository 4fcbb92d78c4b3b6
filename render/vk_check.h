#pragma once
// Every VkResult is checked. Inside render/ a failed call throws VulkanError (the driver
// failing is exceptional and unwinds through RAII owners); render/'s public entry points
// catch it and hand callers a Result with ErrorKind::Gpu.

#include <stdexcept>
#include <string>

#include <vulkan/vulkan.h>

#include "core/result.h"

namespace vegstream::render {

class VulkanError : public std::runtime_error {
 public:
  VulkanError(VkResult result, const std::string& what);
  VkResult result() const { return result_; }

 private:
  VkResult result_;
};

const char* vkResultName(VkResult result);

// Throws VulkanError naming the call when result is an error code.
inline void vkCheck(VkResult result, const char* what) {
  if (result < 0) throw VulkanError(result, what);
}

// Runs fn, turning a VulkanError into an Error value for callers outside render/.
template <typename Fn>
auto guardGpu(Fn&& fn) -> decltype(fn()) {
  try {
    return fn();
  } catch (const VulkanError& e) {
    return makeError(ErrorKind::Gpu, e.what());
  }
}

}  // namespace vegstream::render
