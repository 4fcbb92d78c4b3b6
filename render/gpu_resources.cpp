#include "render/gpu_resources.h"

#include <algorithm>
#include <atomic>
#include <cstring>
#include <stdexcept>
#include <utility>
#include <vector>

#include "render/vk_check.h"

namespace vegstream::render {
namespace {
std::atomic<uint64_t> gDeviceBytes{0};

// One dedicated, named allocation for a buffer or image's requirements.
DeviceAllocation allocate(const Context& ctx, const VkMemoryRequirements& req, VkMemoryPropertyFlags flags,
                          const std::string& name) {
  VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  mai.allocationSize = req.size;
  mai.memoryTypeIndex = ctx.findMemoryType(req.memoryTypeBits, flags);
  VkDeviceMemory mem;
  vkCheck(vkAllocateMemory(ctx.device(), &mai, nullptr, &mem), "vkAllocateMemory");
  ctx.setName(VK_OBJECT_TYPE_DEVICE_MEMORY, mem, name + " memory");
  return DeviceAllocation(DeviceMemory(ctx.device(), mem), req.size);
}
}  // namespace

DeviceAllocation::DeviceAllocation(DeviceMemory memory, VkDeviceSize bytes)
    : memory_(std::move(memory)), bytes_(bytes) {
  gDeviceBytes.fetch_add(bytes_, std::memory_order_relaxed);
}
DeviceAllocation::DeviceAllocation(DeviceAllocation&& o) noexcept
    : memory_(std::move(o.memory_)), bytes_(std::exchange(o.bytes_, 0)) {}
DeviceAllocation& DeviceAllocation::operator=(DeviceAllocation&& o) noexcept {
  if (this != &o) {
    reset();
    memory_ = std::move(o.memory_);
    bytes_ = std::exchange(o.bytes_, 0);
  }
  return *this;
}
void DeviceAllocation::reset() {
  memory_.reset();
  gDeviceBytes.fetch_sub(std::exchange(bytes_, 0), std::memory_order_relaxed);
}
uint64_t deviceMemoryInUse() { return gDeviceBytes.load(std::memory_order_relaxed); }

GpuBuffer createBuffer(const Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUse use,
                       const std::string& name) {
  VkDevice device = ctx.device();
  VkBufferCreateInfo bci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  bci.size = size;
  bci.usage = usage;
  bci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VkBuffer raw;
  vkCheck(vkCreateBuffer(device, &bci, nullptr, &raw), "vkCreateBuffer");
  GpuBuffer out;
  out.buffer = Buffer(device, raw);
  out.size = size;
  ctx.setName(VK_OBJECT_TYPE_BUFFER, raw, name);

  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(device, raw, &req);
  const VkMemoryPropertyFlags flags = use == MemoryUse::DeviceLocal
                                          ? VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT
                                          : VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  out.memory = allocate(ctx, req, flags, name);
  vkCheck(vkBindBufferMemory(device, raw, out.memory.get(), 0), "vkBindBufferMemory");
  if (use != MemoryUse::DeviceLocal)
    vkCheck(vkMapMemory(device, out.memory.get(), 0, VK_WHOLE_SIZE, 0, &out.mapped), "vkMapMemory");
  return out;
}

GpuBuffer createBufferWithData(const Context& ctx, const void* bytes, VkDeviceSize size, VkBufferUsageFlags usage,
                               const std::string& name) {
  GpuBuffer staging =
      createBuffer(ctx, size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::HostUpload, name + " staging");
  std::memcpy(staging.mapped, bytes, static_cast<size_t>(size));
  GpuBuffer out = createBuffer(ctx, size, usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::DeviceLocal, name);
  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    VkBufferCopy region{0, 0, size};
    vkCmdCopyBuffer(cmd, staging.get(), out.get(), 1, &region);
  });
  return out;
}

namespace {
// What creates the image `img` describes (format, extent, depth, layers, mip levels, samples):
// optimal tiling, undefined contents; mutable format when it is also viewed as another.
VkImageCreateInfo imageCreateInfo(const GpuImage& img, VkImageViewType viewType, VkImageUsageFlags usage,
                                  bool alsoViewed) {
  VkImageCreateInfo ici{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  ici.imageType = viewType == VK_IMAGE_VIEW_TYPE_3D ? VK_IMAGE_TYPE_3D : VK_IMAGE_TYPE_2D;
  ici.format = img.format;
  ici.extent = {img.extent.width, img.extent.height, img.depth};
  ici.mipLevels = img.mipLevels;
  ici.arrayLayers = img.layers;
  ici.samples = img.samples;
  ici.tiling = VK_IMAGE_TILING_OPTIMAL;
  ici.usage = usage;
  ici.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  if (alsoViewed) ici.flags |= VK_IMAGE_CREATE_MUTABLE_FORMAT_BIT | VK_IMAGE_CREATE_EXTENDED_USAGE_BIT;
  return ici;
}

// A 2D image (or array), or with a 3D view type a 3D image of `depth` slices.
GpuImage createImage(const Context& ctx, VkExtent2D extent, uint32_t layers, VkFormat format, VkImageUsageFlags usage,
                     VkSampleCountFlagBits samples, VkImageViewType viewType, const std::string& name,
                     uint32_t mipLevels = 1, VkFormat alsoViewAs = VK_FORMAT_UNDEFINED, uint32_t depth = 1) {
  VkDevice device = ctx.device();
  GpuImage out;
  out.format = format;
  out.extent = extent;
  out.depth = depth;
  out.layers = layers;
  out.mipLevels = mipLevels;
  out.samples = samples;
  out.aspect = (format == VK_FORMAT_D32_SFLOAT || format == VK_FORMAT_D16_UNORM) ? VK_IMAGE_ASPECT_DEPTH_BIT
                                                                                 : VK_IMAGE_ASPECT_COLOR_BIT;
  const VkImageCreateInfo ici = imageCreateInfo(out, viewType, usage, alsoViewAs != VK_FORMAT_UNDEFINED);
  VkImage raw;
  vkCheck(vkCreateImage(device, &ici, nullptr, &raw), "vkCreateImage");
  out.image = Image(device, raw);
  ctx.setName(VK_OBJECT_TYPE_IMAGE, raw, name);

  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(device, raw, &req);
  out.memory = allocate(ctx, req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, name);
  out.bytes = req.size;
  vkCheck(vkBindImageMemory(device, raw, out.memory.get(), 0), "vkBindImageMemory");

  VkImageViewCreateInfo vci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  vci.image = raw;
  vci.viewType = viewType;
  vci.format = format;
  vci.subresourceRange = {out.aspect, 0, mipLevels, 0, layers};
  // With a second format the image may carry a usage only that format supports (storage on an
  // sRGB target): the primary view leaves storage out.
  VkImageViewUsageCreateInfo primaryUsage{VK_STRUCTURE_TYPE_IMAGE_VIEW_USAGE_CREATE_INFO};
  primaryUsage.usage = usage & ~VkImageUsageFlags{VK_IMAGE_USAGE_STORAGE_BIT};
  if (alsoViewAs != VK_FORMAT_UNDEFINED) vci.pNext = &primaryUsage;
  VkImageView view;
  vkCheck(vkCreateImageView(device, &vci, nullptr, &view), "vkCreateImageView");
  out.view = ImageView(device, view);
  ctx.setName(VK_OBJECT_TYPE_IMAGE_VIEW, view, name + " view");
  if (alsoViewAs != VK_FORMAT_UNDEFINED) {
    vci.pNext = nullptr;
    vci.format = alsoViewAs;
    vkCheck(vkCreateImageView(device, &vci, nullptr, &view), "vkCreateImageView");
    out.alternateView = ImageView(device, view);
    ctx.setName(VK_OBJECT_TYPE_IMAGE_VIEW, view, name + " view as another format");
  }
  return out;
}
}  // namespace

GpuImage createImage2D(const Context& ctx, VkExtent2D extent, VkFormat format, VkImageUsageFlags usage,
                       VkSampleCountFlagBits samples, const std::string& name, VkFormat alsoViewAs) {
  return createImage(ctx, extent, 1, format, usage, samples, VK_IMAGE_VIEW_TYPE_2D, name, 1, alsoViewAs);
}

GpuImage createImage3D(const Context& ctx, VkExtent2D extent, uint32_t depth, VkFormat format, VkImageUsageFlags usage,
                       const std::string& name) {
  return createImage(ctx, extent, 1, format, usage, VK_SAMPLE_COUNT_1_BIT, VK_IMAGE_VIEW_TYPE_3D, name, 1,
                     VK_FORMAT_UNDEFINED, depth);
}

GpuImage createImageArray(const Context& ctx, VkExtent2D extent, uint32_t layers, VkFormat format,
                          VkImageUsageFlags usage, const std::string& name, uint32_t mipLevels, VkFormat alsoViewAs) {
  return createImage(ctx, extent, layers, format, usage, VK_SAMPLE_COUNT_1_BIT, VK_IMAGE_VIEW_TYPE_2D_ARRAY, name,
                     mipLevels, alsoViewAs);
}

namespace {
// b (a VkMemoryBarrier2 or a VkImageMemoryBarrier2) waits for srcAccess in srcStage before
// dstAccess in dstStage.
template <class Barrier>
void setScopes(Barrier& b, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStage,
               VkAccessFlags2 dstAccess) {
  b.srcStageMask = srcStage;
  b.srcAccessMask = srcAccess;
  b.dstStageMask = dstStage;
  b.dstAccessMask = dstAccess;
}

// Records one barrier: a global memory barrier or an image's (the other null).
void pipelineBarrier(VkCommandBuffer cmd, const VkMemoryBarrier2* memory, const VkImageMemoryBarrier2* image) {
  VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dep.memoryBarrierCount = memory ? 1 : 0;
  dep.pMemoryBarriers = memory;
  dep.imageMemoryBarrierCount = image ? 1 : 0;
  dep.pImageMemoryBarriers = image;
  vkCmdPipelineBarrier2(cmd, &dep);
}

// The bytes of one texel of the uncompressed colour formats uploaded whole (recordImageArrayUpload).
VkDeviceSize texelBytes(VkFormat format) {
  switch (format) {
    case VK_FORMAT_R8_UNORM: return 1;
    case VK_FORMAT_R8G8B8A8_UNORM:
    case VK_FORMAT_R8G8B8A8_SRGB: return 4;
    case VK_FORMAT_R32G32B32A32_SFLOAT: return 16;
    default: throw std::logic_error("recordImageArrayUpload: no texel size for this format");
  }
}
}  // namespace

void transitionImageRange(VkCommandBuffer cmd, VkImage image, const VkImageSubresourceRange& range, VkImageLayout from,
                          VkImageLayout to, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                          VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess) {
  VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  setScopes(b, srcStage, srcAccess, dstStage, dstAccess);
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;  // no ownership transfer
  b.image = image;
  b.subresourceRange = range;
  pipelineBarrier(cmd, nullptr, &b);
}

void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                   VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess) {
  VkMemoryBarrier2 mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
  setScopes(mb, srcStage, srcAccess, dstStage, dstAccess);
  pipelineBarrier(cmd, &mb, nullptr);
}

void hostReadBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess) {
  memoryBarrier(cmd, srcStage, srcAccess, VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
}

void transitionImage(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout from,
                     VkImageLayout to, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                     VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess) {
  transitionImageRange(cmd, image, {aspect, 0, 1, 0, 1}, from, to, srcStage, srcAccess, dstStage, dstAccess);
}

void recordSampledImageReadback(VkCommandBuffer cmd, VkImage image, const VkImageSubresourceLayers& layers,
                                VkExtent3D extent, const GpuBuffer& host, VkDeviceSize hostOffset,
                                VkPipelineStageFlags2 readers) {
  const VkImageSubresourceRange range{layers.aspectMask, layers.mipLevel, 1, layers.baseArrayLayer, layers.layerCount};
  transitionImageRange(cmd, image, range, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                       VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readers, 0, VK_PIPELINE_STAGE_2_COPY_BIT,
                       VK_ACCESS_2_TRANSFER_READ_BIT);
  VkBufferImageCopy region{};
  region.bufferOffset = hostOffset;
  region.imageSubresource = layers;
  region.imageExtent = extent;
  vkCmdCopyImageToBuffer(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, host.get(), 1, &region);
  transitionImageRange(cmd, image, range, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                       VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT, 0, readers,
                       VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
}

void recordImageUpload(VkCommandBuffer cmd, const GpuBuffer& staging, const GpuImage& image, uint32_t layer,
                       VkDeviceSize stagingOffset) {
  const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, layer, 1};
  // After every earlier command on the queue: a frame still in flight may read the layer's old
  // tile (with three frames in flight the streamer's reuse delay alone does not order that).
  transitionImageRange(cmd, image.get(), range, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                       VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0, VK_PIPELINE_STAGE_2_COPY_BIT,
                       VK_ACCESS_2_TRANSFER_WRITE_BIT);
  VkBufferImageCopy region{};
  region.bufferOffset = stagingOffset;
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, layer, 1};
  region.imageExtent = {image.extent.width, image.extent.height, 1};
  vkCmdCopyBufferToImage(cmd, staging.get(), image.get(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
  transitionImageRange(cmd, image.get(), range, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                       VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT,
                       VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                       VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
}

VkDeviceSize recordImageArrayUpload(VkCommandBuffer cmd, const GpuBuffer& staging, const GpuImage& image,
                                    VkPipelineStageFlags2 readers) {
  const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, image.mipLevels, 0, image.layers};
  transitionImageRange(cmd, image.get(), all, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                       VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  std::vector<VkBufferImageCopy> regions;
  VkDeviceSize offset = 0;
  for (uint32_t layer = 0; layer < image.layers; ++layer)
    for (uint32_t mip = 0; mip < image.mipLevels; ++mip) {
      const uint32_t w = std::max(image.extent.width >> mip, 1u), h = std::max(image.extent.height >> mip, 1u);
      VkBufferImageCopy region{};
      region.bufferOffset = offset;
      region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, mip, layer, 1};
      region.imageExtent = {w, h, 1};
      regions.push_back(region);
      offset += VkDeviceSize{w} * h * texelBytes(image.format);
    }
  vkCmdCopyBufferToImage(cmd, staging.get(), image.get(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                         static_cast<uint32_t>(regions.size()), regions.data());
  transitionImageRange(cmd, image.get(), all, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                       VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT,
                       VK_ACCESS_2_TRANSFER_WRITE_BIT, readers, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  return offset;
}

}  // namespace vegstream::render
