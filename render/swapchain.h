#pragma once
// A window surface and its swapchain (GLFW creates the surface). Recreated when the window
// changes size or the driver reports it out of date.

#include <cstdint>
#include <optional>
#include <vector>

#include "render/context.h"
#include "render/handle.h"

struct GLFWwindow;

namespace vegstream::render {

class Swapchain {
 public:
  Swapchain(const Context& ctx, GLFWwindow* window);
  ~Swapchain();
  Swapchain(const Swapchain&) = delete;
  Swapchain& operator=(const Swapchain&) = delete;

  // The next image to draw into, or nullopt when the swapchain had to be recreated (skip
  // presenting this frame). `signal` is signalled when the image may be written.
  std::optional<uint32_t> acquire(VkSemaphore signal);
  // Presents image `index` after `wait`; recreates the swapchain if it went out of date.
  void present(uint32_t index, VkSemaphore wait);

  VkImage image(uint32_t index) const { return images_[index]; }
  VkExtent2D extent() const { return extent_; }
  VkSemaphore renderDone(uint32_t index) const { return renderDone_[index].get(); }

 private:
  void create();
  void destroySwapchain();

  const Context* ctx_;
  GLFWwindow* window_;
  VkSurfaceKHR surface_ = VK_NULL_HANDLE;
  VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  VkExtent2D extent_{};
  std::vector<VkImage> images_;
  std::vector<Semaphore> renderDone_;  // one per image: presentation may still read it
};

}  // namespace vegstream::render
