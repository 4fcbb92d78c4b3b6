// The sun's cascaded shadow map (sun_shadow_pass.h).
#include "render/sun_shadow_pass.h"

#include <cstring>
#include <vector>

#include "render/descriptors.h"
#include "render/vk_check.h"

namespace vegstream::render {
namespace {

constexpr VkFormat kShadowFormat = VK_FORMAT_R32_UINT;  // reverse-Z depths as float bits
constexpr VkPipelineStageFlags2 kReaders =
    VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT |
    VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_GEOMETRY_SHADER_BIT |
    VK_PIPELINE_STAGE_2_TESSELLATION_EVALUATION_SHADER_BIT;
constexpr VkAccessFlags2 kCasterAccess = VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;

VkImageSubresourceRange layers(uint32_t first, uint32_t count) {
  return {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, first, count};
}

}  // namespace

SunShadowPass::SunShadowPass(const Context& ctx, uint32_t mapSize) : ctx_(&ctx), size_(mapSize) {
  map_ = createImageArray(ctx, {mapSize, mapSize}, kShadowCascades, kShadowFormat,
                          VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                              VK_IMAGE_USAGE_TRANSFER_SRC_BIT,  // read back by tests (read())
                          "sun shadow map");
  placeholder_ =
      createImageArray(ctx, {1, 1}, kShadowCascades, kShadowFormat,
                       VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, "sun shadow placeholder");
  // Texels read exactly (textureGather); sun_shadow.glsl compares and filters.
  sampler_ = createNearestClampSampler(ctx, "sun shadow sampler");
  targetLayout_ = createSingleBindingLayout(ctx, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT,
                                            "sun shadow target layout");
  targetPool_ = createSingleBindingPool(ctx, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, "sun shadow target pool");
  targetSet_ = allocateDescriptorSet(ctx, targetPool_.get(), targetLayout_.get(), "sun shadow target");
  writeStorageImage(ctx, targetSet_, map_.view.get(), 0);
  // Cleared to the far plane: nothing casts until a frame draws casters.
  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    const VkImageSubresourceRange all = layers(0, kShadowCascades);
    for (const GpuImage* img : {&map_, &placeholder_}) {
      transitionImageRange(cmd, img->get(), all, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                           VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
      const VkClearColorValue clear{};
      vkCmdClearColorImage(cmd, img->get(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &clear, 1, &all);
      transitionImageRange(cmd, img->get(), all, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                           VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_CLEAR_BIT,
                           VK_ACCESS_2_TRANSFER_WRITE_BIT, kReaders, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    }
  });
}

void SunShadowPass::writeFrameSet(VkDescriptorSet frameSet, bool placeholder) const {
  writeSampledImage(*ctx_, frameSet, sampler_.get(), (placeholder ? placeholder_ : map_).view.get(), 4);
}

void SunShadowPass::record(VkCommandBuffer cmd, const ShadowCascades& cascades, const DrawCasters& draw) const {
  const VkImageSubresourceRange all = layers(0, kShadowCascades);
  // Earlier frames' reads finish before the map is written again; the kept layers keep their
  // contents through the layout changes.
  transitionImageRange(cmd, map_.get(), all, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL,
                       kReaders, 0, VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  std::vector<VkImageSubresourceRange> drawn;
  for (int c = 0; c < kShadowCascades; ++c)
    if ((cascades.drawn & (1u << c)) != 0) drawn.push_back(layers(static_cast<uint32_t>(c), 1));
  const VkClearColorValue far{};  // depth 0: the far plane
  if (!drawn.empty())
    vkCmdClearColorImage(cmd, map_.get(), VK_IMAGE_LAYOUT_GENERAL, &far, static_cast<uint32_t>(drawn.size()),
                         drawn.data());
  transitionImageRange(cmd, map_.get(), all, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_GENERAL,
                       VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, kCasterAccess);
  for (int c = 0; c < kShadowCascades; ++c)
    if ((cascades.drawn & (1u << c)) != 0) draw(cmd, c, cascades.matrices[size_t(c)], targetSet_);
  transitionImageRange(cmd, map_.get(), all, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                       VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, kCasterAccess, kReaders,
                       VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
}

std::vector<uint32_t> SunShadowPass::read() const {
  const VkDeviceSize bytes = VkDeviceSize{size_} * size_ * kShadowCascades * sizeof(uint32_t);
  GpuBuffer buffer =
      createBuffer(*ctx_, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::HostReadback, "sun shadow read-back");
  ctx_->submitAndWait([&](VkCommandBuffer cmd) {
    recordSampledImageReadback(cmd, map_.get(), {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, uint32_t{kShadowCascades}},
                               {size_, size_, 1}, buffer, 0, kReaders);
    hostReadBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  });
  std::vector<uint32_t> out(static_cast<size_t>(bytes / sizeof(uint32_t)));
  std::memcpy(out.data(), buffer.mapped, static_cast<size_t>(bytes));
  return out;
}

}  // namespace vegstream::render
