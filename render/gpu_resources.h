#pragma once
// Buffers and images with their own memory (one allocation each: vegstream holds tens of GPU
// objects, not thousands, so a sub-allocator would be complexity without benefit yet).

#include <cstddef>
#include <string>

#include "render/context.h"
#include "render/handle.h"

namespace vegstream::render {

// Device memory whose size counts in a process-wide total while it lives: every buffer's and
// image's memory is one (the allocation below), so deviceMemoryInUse() is what vegstream holds
// on the GPU (the soak's figure, scripts/soak).
class DeviceAllocation {
 public:
  DeviceAllocation() = default;
  DeviceAllocation(DeviceMemory memory, VkDeviceSize bytes);
  ~DeviceAllocation() { reset(); }
  DeviceAllocation(DeviceAllocation&& o) noexcept;
  DeviceAllocation& operator=(DeviceAllocation&& o) noexcept;
  DeviceAllocation(const DeviceAllocation&) = delete;
  DeviceAllocation& operator=(const DeviceAllocation&) = delete;

  VkDeviceMemory get() const { return memory_.get(); }
  VkDeviceSize bytes() const { return bytes_; }
  void reset();

 private:
  DeviceMemory memory_;
  VkDeviceSize bytes_ = 0;
};
// Bytes of every DeviceAllocation alive in this process. Any thread.
uint64_t deviceMemoryInUse();

struct GpuBuffer {
  Buffer buffer;
  DeviceAllocation memory;
  VkDeviceSize size = 0;
  void* mapped = nullptr;  // persistently mapped when host-visible

  VkBuffer get() const { return buffer.get(); }
};

enum class MemoryUse { DeviceLocal, HostUpload, HostReadback };

// The size a growing per-frame buffer is given: `minimum`, doubled until it holds `needed`
// (so a slowly growing scene reallocates rarely).
inline VkDeviceSize grownSize(VkDeviceSize needed, VkDeviceSize minimum = 64 * 1024) {
  VkDeviceSize size = minimum;
  while (size < needed) size *= 2;
  return size;
}

GpuBuffer createBuffer(const Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUse use,
                       const std::string& name);

// A device-local buffer filled with `bytes` through a staging copy (waits for the copy).
GpuBuffer createBufferWithData(const Context& ctx, const void* bytes, VkDeviceSize size, VkBufferUsageFlags usage,
                               const std::string& name);

struct GpuImage {
  Image image;
  DeviceAllocation memory;
  ImageView view;
  ImageView alternateView;  // the same texels in the format asked for as `alsoViewAs` (else null)
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkExtent2D extent{};
  VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
  VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;
  uint32_t layers = 1;
  uint32_t depth = 1;  // a 3D image's slices
  uint32_t mipLevels = 1;
  VkDeviceSize bytes = 0;  // device memory it holds

  VkImage get() const { return image.get(); }
};

// `alsoViewAs`: a second format the texels are viewed as (GpuImage::alternateView); the image
// may then have usages only that format supports (e.g. storage on an sRGB target seen as UNORM).
GpuImage createImage2D(const Context& ctx, VkExtent2D extent, VkFormat format, VkImageUsageFlags usage,
                       VkSampleCountFlagBits samples, const std::string& name,
                       VkFormat alsoViewAs = VK_FORMAT_UNDEFINED);

// A single-sampled colour image of `layers` array layers (each with `mipLevels` levels) with a
// 2D-array view of all of them.
// A 3D image (one level, single sample) of `depth` slices with a 3D view.
GpuImage createImage3D(const Context& ctx, VkExtent2D extent, uint32_t depth, VkFormat format, VkImageUsageFlags usage,
                       const std::string& name);
GpuImage createImageArray(const Context& ctx, VkExtent2D extent, uint32_t layers, VkFormat format,
                          VkImageUsageFlags usage, const std::string& name, uint32_t mipLevels = 1,
                          VkFormat alsoViewAs = VK_FORMAT_UNDEFINED);

// One pipeline barrier for a subresource range of an image (synchronization2).
void transitionImageRange(VkCommandBuffer cmd, VkImage image, const VkImageSubresourceRange& range, VkImageLayout from,
                          VkImageLayout to, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                          VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess);

// One pipeline barrier for one whole single-layer image (synchronization2).
// Makes writes of `srcStage` / `srcAccess` visible to the host once the submission's fence
// signals (read-backs of images or storage buffers).
// A global memory barrier (synchronization2): writes of `srcStage` made visible to `dstStage`.
void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                   VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess);
void hostReadBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess);
void transitionImage(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout from,
                     VkImageLayout to, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                     VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess);

// Records the copy of `layers` (one mip level) of a sampled image, in SHADER_READ_ONLY_OPTIMAL
// for `readers`, into `host` at `hostOffset`, tightly packed, and leaves the image as it was;
// the caller adds hostReadBarrier once its copies are recorded (read-backs for tests and tools).
void recordSampledImageReadback(VkCommandBuffer cmd, VkImage image, const VkImageSubresourceLayers& layers,
                                VkExtent3D extent, const GpuBuffer& host, VkDeviceSize hostOffset,
                                VkPipelineStageFlags2 readers);

// Records the copy of a tightly packed staging buffer (from stagingOffset) into one layer of
// `image` (mip 0),
// leaving it in SHADER_READ_ONLY_OPTIMAL for fragment shaders. The image's old contents are
// discarded, after every earlier command on the queue (frames in flight) has read them; the
// staging buffer must live until the commands complete.
void recordImageUpload(VkCommandBuffer cmd, const GpuBuffer& staging, const GpuImage& image, uint32_t layer = 0,
                       VkDeviceSize stagingOffset = 0);

// Records the copy of every layer and mip level of `image` (R8, RGBA8 or RGBA32F texels) from a
// tightly packed staging buffer holding layer 0 (mip 0, mip 1, …), then layer 1, …, leaving the
// whole image in SHADER_READ_ONLY_OPTIMAL for `readers`. Returns the bytes consumed.
VkDeviceSize recordImageArrayUpload(VkCommandBuffer cmd, const GpuBuffer& staging, const GpuImage& image,
                                    VkPipelineStageFlags2 readers = VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT);

}  // namespace vegstream::render
