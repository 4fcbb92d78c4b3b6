// What one frame in flight owns (frame_slot.h): set 0's layout and pool, the slot's command
// buffer, sync objects, uniforms, timer and read-back buffers, and the images read back.
#include "render/frame_slot.h"

#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "render/aov_image.h"
#include "render/descriptors.h"
#include "render/frame_slots.h"
#include "render/frame_uniforms.h"
#include "render/vk_check.h"

namespace vegstream::render {

DescriptorSetLayout createFrameSetLayout(const Context& ctx) {
  constexpr VkShaderStageFlags kFrameStages = VK_SHADER_STAGE_ALL_GRAPHICS | VK_SHADER_STAGE_COMPUTE_BIT;
  const VkDescriptorSetLayoutBinding frameBindings[] = {
      {0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, kFrameStages, nullptr},
      {1, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, kFrameStages, nullptr},
      {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, kFrameStages, nullptr},
      {3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, kFrameStages, nullptr},
      {4, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, kFrameStages, nullptr},  // the sun's shadow map
      {5, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, kFrameStages, nullptr},          // the compute raster's terrain depth
      {6, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, kFrameStages, nullptr},          // the Hi-Z pyramid
      {7, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, kFrameStages, nullptr},  // the sky-view LUT
      {8, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, kFrameStages, nullptr},  // the aerial-perspective volume
      {9, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, kFrameStages, nullptr},  // the sky light (render/atmosphere_pass.h)
      {10, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, kFrameStages,
       nullptr}};  // the depth tile marks (terrain_depth_handover.h)
  return createLayout(ctx, frameBindings, "frame set layout");
}

DescriptorPool createFrameSetPool(const Context& ctx) {
  const VkDescriptorPoolSize frameSizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 2 * kFramesInFlight},
                                             {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 6 * kFramesInFlight},
                                             {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 3 * kFramesInFlight}};
  // Twice: each slot has a second set for the shadow pass (its binding 4 a placeholder map).
  VkDescriptorPoolSize doubled[3];
  for (int k = 0; k < 3; ++k) doubled[k] = {frameSizes[k].type, 2 * frameSizes[k].descriptorCount};
  return createPool(ctx, doubled, 2 * kFramesInFlight, "frame descriptor pool");
}

void createFrameSlot(const Context& ctx, FrameSlot& s, int index, VkDeviceSize pixels) {
  const std::string tag = " (slot " + std::to_string(index) + ")";
  VkCommandPoolCreateInfo cpci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  cpci.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
  cpci.queueFamilyIndex = ctx.queueFamily();
  VkCommandPool cp;
  vkCheck(vkCreateCommandPool(ctx.device(), &cpci, nullptr, &cp), "vkCreateCommandPool");
  s.pool = CommandPool(ctx.device(), cp);
  ctx.setName(VK_OBJECT_TYPE_COMMAND_POOL, cp, "frame command pool" + tag);
  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ai.commandPool = cp;
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  vkCheck(vkAllocateCommandBuffers(ctx.device(), &ai, &s.cmd), "vkAllocateCommandBuffers");
  ctx.setName(VK_OBJECT_TYPE_COMMAND_BUFFER, s.cmd, "frame commands" + tag);
  VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VkFence fence;
  vkCheck(vkCreateFence(ctx.device(), &fci, nullptr, &fence), "vkCreateFence");
  s.fence = Fence(ctx.device(), fence);
  ctx.setName(VK_OBJECT_TYPE_FENCE, fence, "frame fence" + tag);
  VkSemaphoreCreateInfo sci{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  VkSemaphore sem;
  vkCheck(vkCreateSemaphore(ctx.device(), &sci, nullptr, &sem), "vkCreateSemaphore");
  s.imageAcquired = Semaphore(ctx.device(), sem);
  ctx.setName(VK_OBJECT_TYPE_SEMAPHORE, sem, "image acquired" + tag);
  s.uniforms = createBuffer(ctx, sizeof(FrameUniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, MemoryUse::HostUpload,
                            "frame uniforms" + tag);
  s.timer = std::make_unique<GpuTimer>(ctx, kMaxPasses, "frame" + tag);
  s.colorReadback = createBuffer(ctx, pixels * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::HostReadback,
                                 "colour read-back" + tag);
  s.depthReadback =
      createBuffer(ctx, pixels * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::HostReadback, "depth read-back" + tag);
}

void readSlotImages(const FrameSlot& slot, VkExtent2D e, FrameResult& r) {
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
  if (slot.readAov && r.depth)
    r.aov = decodeAov(e.width, e.height, static_cast<const uint32_t*>(slot.aovReadback.mapped), r.depth->depth.data(),
                      slot.aovInverseProjection);
}

}  // namespace vegstream::render
