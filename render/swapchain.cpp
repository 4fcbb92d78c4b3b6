#include "render/swapchain.h"

#include <algorithm>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include "render/vk_check.h"

namespace vegstream::render {

Swapchain::Swapchain(const Context& ctx, GLFWwindow* window) : ctx_(&ctx), window_(window) {
  vkCheck(glfwCreateWindowSurface(ctx.instance(), window, nullptr, &surface_), "glfwCreateWindowSurface");
  VkBool32 supported = VK_FALSE;
  vkCheck(vkGetPhysicalDeviceSurfaceSupportKHR(ctx.physicalDevice(), ctx.queueFamily(), surface_, &supported),
          "vkGetPhysicalDeviceSurfaceSupportKHR");
  if (!supported) throw VulkanError(VK_ERROR_INITIALIZATION_FAILED, "presenting to the window from the graphics queue");
  create();
}

Swapchain::~Swapchain() {
  vkDeviceWaitIdle(ctx_->device());
  destroySwapchain();
  if (surface_) vkDestroySurfaceKHR(ctx_->instance(), surface_, nullptr);
}

void Swapchain::destroySwapchain() {
  renderDone_.clear();
  images_.clear();
  if (swapchain_) vkDestroySwapchainKHR(ctx_->device(), swapchain_, nullptr);
  swapchain_ = VK_NULL_HANDLE;
}

void Swapchain::create() {
  VkPhysicalDevice pd = ctx_->physicalDevice();
  VkSurfaceCapabilitiesKHR caps;
  vkCheck(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(pd, surface_, &caps), "vkGetPhysicalDeviceSurfaceCapabilitiesKHR");
  uint32_t n = 0;
  vkCheck(vkGetPhysicalDeviceSurfaceFormatsKHR(pd, surface_, &n, nullptr), "vkGetPhysicalDeviceSurfaceFormatsKHR");
  std::vector<VkSurfaceFormatKHR> formats(n);
  vkCheck(vkGetPhysicalDeviceSurfaceFormatsKHR(pd, surface_, &n, formats.data()),
          "vkGetPhysicalDeviceSurfaceFormatsKHR");
  VkSurfaceFormatKHR chosen = formats.at(0);
  for (const auto& f : formats)
    if (f.format == VK_FORMAT_B8G8R8A8_SRGB || f.format == VK_FORMAT_R8G8B8A8_SRGB) chosen = f;
  format_ = chosen.format;

  int w = 0, h = 0;
  glfwGetFramebufferSize(window_, &w, &h);
  extent_ = caps.currentExtent;
  if (extent_.width == UINT32_MAX) {
    extent_.width =
        std::clamp(static_cast<uint32_t>(std::max(w, 1)), caps.minImageExtent.width, caps.maxImageExtent.width);
    extent_.height =
        std::clamp(static_cast<uint32_t>(std::max(h, 1)), caps.minImageExtent.height, caps.maxImageExtent.height);
  }
  VkSwapchainCreateInfoKHR ci{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
  ci.surface = surface_;
  ci.minImageCount =
      caps.maxImageCount == 0 ? caps.minImageCount + 1 : std::min(caps.minImageCount + 1, caps.maxImageCount);
  ci.imageFormat = chosen.format;
  ci.imageColorSpace = chosen.colorSpace;
  ci.imageExtent = extent_;
  ci.imageArrayLayers = 1;
  ci.imageUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT;  // the resolved frame is blitted in
  ci.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  ci.preTransform = caps.currentTransform;
  ci.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
  ci.presentMode = VK_PRESENT_MODE_FIFO_KHR;  // always available
  ci.clipped = VK_TRUE;
  vkCheck(vkCreateSwapchainKHR(ctx_->device(), &ci, nullptr, &swapchain_), "vkCreateSwapchainKHR");
  ctx_->setName(VK_OBJECT_TYPE_SWAPCHAIN_KHR, swapchain_, "window swapchain");
  vkCheck(vkGetSwapchainImagesKHR(ctx_->device(), swapchain_, &n, nullptr), "vkGetSwapchainImagesKHR");
  images_.resize(n);
  vkCheck(vkGetSwapchainImagesKHR(ctx_->device(), swapchain_, &n, images_.data()), "vkGetSwapchainImagesKHR");
  for (uint32_t i = 0; i < n; ++i) {
    VkSemaphoreCreateInfo sci{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    VkSemaphore s;
    vkCheck(vkCreateSemaphore(ctx_->device(), &sci, nullptr, &s), "vkCreateSemaphore");
    renderDone_.emplace_back(ctx_->device(), s);
    ctx_->setName(VK_OBJECT_TYPE_SEMAPHORE, s, "render done " + std::to_string(i));
  }
}

std::optional<uint32_t> Swapchain::acquire(VkSemaphore signal) {
  uint32_t index = 0;
  const VkResult r = vkAcquireNextImageKHR(ctx_->device(), swapchain_, UINT64_MAX, signal, VK_NULL_HANDLE, &index);
  if (r == VK_ERROR_OUT_OF_DATE_KHR) {
    vkDeviceWaitIdle(ctx_->device());
    destroySwapchain();
    create();
    return std::nullopt;
  }
  vkCheck(r, "vkAcquireNextImageKHR");
  return index;
}

void Swapchain::present(uint32_t index, VkSemaphore wait) {
  VkPresentInfoKHR pi{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
  pi.waitSemaphoreCount = 1;
  pi.pWaitSemaphores = &wait;
  pi.swapchainCount = 1;
  pi.pSwapchains = &swapchain_;
  pi.pImageIndices = &index;
  const VkResult r = vkQueuePresentKHR(ctx_->queue(), &pi);
  int w = 0, h = 0;
  glfwGetFramebufferSize(window_, &w, &h);
  const bool resized = static_cast<uint32_t>(w) != extent_.width || static_cast<uint32_t>(h) != extent_.height;
  if (r == VK_ERROR_OUT_OF_DATE_KHR || r == VK_SUBOPTIMAL_KHR || (resized && w > 0 && h > 0)) {
    vkDeviceWaitIdle(ctx_->device());
    destroySwapchain();
    create();
    return;
  }
  vkCheck(r, "vkQueuePresentKHR");
}

}  // namespace vegstream::render
