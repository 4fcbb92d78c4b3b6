// Octahedral impostor capture (tree_impostors.h).
#include "render/tree_impostors.h"

#include <cassert>
#include <cmath>
#include <cstring>
#include <string>

#include <glm/geometric.hpp>

#include "render/vk_check.h"

namespace vegstream::render {
namespace {

constexpr VkFormat kAtlasFormat = VK_FORMAT_R8G8B8A8_UNORM;
constexpr VkFormat kCaptureDepth = VK_FORMAT_D32_SFLOAT;

ImageView layerView(const Context& ctx, const GpuImage& image, uint32_t layer, VkImageAspectFlags aspect) {
  VkImageViewCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  ci.image = image.get();
  ci.viewType = VK_IMAGE_VIEW_TYPE_2D;
  ci.format = image.format;
  ci.subresourceRange = {aspect, 0, 1, layer, 1};
  VkImageView view = VK_NULL_HANDLE;
  vkCheck(vkCreateImageView(ctx.device(), &ci, nullptr, &view), "vkCreateImageView(impostor layer)");
  return ImageView(ctx.device(), view);
}

void createAtlases(const Context& ctx, uint32_t layers, GpuImage& albedo, GpuImage& normal) {
  const uint32_t side = kImpostorViews * kImpostorCellPx;
  const VkImageUsageFlags usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                                  VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  albedo = createImageArray(ctx, {side, side}, layers, kAtlasFormat, usage, "tree impostor albedo", kImpostorMipLevels);
  normal = createImageArray(ctx, {side, side}, layers, kAtlasFormat, usage, "tree impostor normal + depth",
                            kImpostorMipLevels);
}

}  // namespace

glm::vec3 impostorDirection(glm::vec2 uv) {
  const glm::vec2 ab = uv * 2.0f - 1.0f;
  const glm::vec2 p = glm::vec2(ab.x + ab.y, ab.x - ab.y) * 0.5f;
  return glm::normalize(glm::vec3(p, 1.0f - std::abs(p.x) - std::abs(p.y)));
}

void impostorBasis(glm::vec3 d, glm::vec3& right, glm::vec3& up) {
  const glm::vec3 r = glm::cross(glm::vec3(0.0f, 0.0f, 1.0f), d);
  right = glm::dot(r, r) > 1e-6f ? glm::normalize(r) : glm::vec3(1.0f, 0.0f, 0.0f);
  up = glm::cross(d, right);
}

TreeImpostors::TreeImpostors(const Context& ctx, std::span<const TreeImpostorModel> models, const DrawModel& draw)
    : ctx_(&ctx) {
  assert(!models.empty());
  const uint32_t side = kImpostorViews * kImpostorCellPx;
  const VkExtent2D extent{side, side};
  const auto layers = static_cast<uint32_t>(models.size());
  createAtlases(ctx, layers, albedo_, normal_);
  depth_ = createImage2D(ctx, extent, kCaptureDepth, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, kImpostorSamples,
                         "tree impostor capture depth");
  const bool multisampled = kImpostorSamples != VK_SAMPLE_COUNT_1_BIT;
  if (multisampled) {
    msAlbedo_ = createImage2D(ctx, extent, kAtlasFormat, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, kImpostorSamples,
                              "tree impostor capture albedo (multisampled)");
    msNormal_ = createImage2D(ctx, extent, kAtlasFormat, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, kImpostorSamples,
                              "tree impostor capture normal (multisampled)");
  }
  // The layers' attachment views live until the capture has run (destroyed while the command
  // buffer records, they would leave it pointing at freed views).
  std::vector<ImageView> views;
  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, layers};
    for (const GpuImage* img : {&albedo_, &normal_})
      transitionImageRange(cmd, img->get(), all, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                           VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                           VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
    if (multisampled)
      for (const GpuImage* img : {&msAlbedo_, &msNormal_})
        transitionImage(cmd, img->get(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                      VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, 0,
                      VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
    for (uint32_t layer = 0; layer < layers; ++layer) captureLayer(cmd, layer, views, draw);
    buildMips(cmd, layers);
  });
  // The capture's own targets are not needed after it: the atlases hold the same GPU memory
  // whether captured or read from the cache (tree_gpu_bytes is the same either way).
  depth_ = {};
  msAlbedo_ = {};
  msNormal_ = {};
}

void TreeImpostors::buildMips(VkCommandBuffer cmd, uint32_t layers) const {
  const int32_t side = static_cast<int32_t>(kImpostorViews * kImpostorCellPx);
  for (const GpuImage* img : {&albedo_, &normal_}) {
    // Level 0 → a blit source; then each level a destination, then the next one's source.
    transitionImageRange(cmd, img->get(), {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, layers},
                         VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                         VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                         VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    for (uint32_t level = 1; level < kImpostorMipLevels; ++level) {
      transitionImageRange(cmd, img->get(), {VK_IMAGE_ASPECT_COLOR_BIT, level, 1, 0, layers},
                           VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, 0,
                           VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
      const int32_t from = side >> (level - 1), to = side >> level;
      VkImageBlit blit{};
      blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level - 1, 0, layers};
      blit.srcOffsets[1] = {from, from, 1};
      blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level, 0, layers};
      blit.dstOffsets[1] = {to, to, 1};
      // Exactly half: the linear filter is the 2 × 2 box of the premultiplied texels.
      vkCmdBlitImage(cmd, img->get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, img->get(),
                     VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_LINEAR);
      transitionImageRange(cmd, img->get(), {VK_IMAGE_ASPECT_COLOR_BIT, level, 1, 0, layers},
                           VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                           VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_BLIT_BIT,
                           VK_ACCESS_2_TRANSFER_READ_BIT);
    }
    transitionImageRange(cmd, img->get(), {VK_IMAGE_ASPECT_COLOR_BIT, 0, kImpostorMipLevels, 0, layers},
                         VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                         VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                         VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_COPY_BIT,
                         VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT);
  }
}

void TreeImpostors::captureLayer(VkCommandBuffer cmd, uint32_t layer, std::vector<ImageView>& views,
                                 const DrawModel& draw) {
  const Context& ctx = *ctx_;
  const uint32_t side = kImpostorViews * kImpostorCellPx;
  const VkExtent2D extent{side, side};
  const bool multisampled = kImpostorSamples != VK_SAMPLE_COUNT_1_BIT;
  // The depth target is reused per layer: wait for the previous layer's tests.
  transitionImage(cmd, depth_.get(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                  VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                  VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT,
                  VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT);
  views.push_back(layerView(ctx, albedo_, layer, VK_IMAGE_ASPECT_COLOR_BIT));
  views.push_back(layerView(ctx, normal_, layer, VK_IMAGE_ASPECT_COLOR_BIT));
  VkRenderingAttachmentInfo colour[2]{};
  for (int k = 0; k < 2; ++k) {
    colour[k].sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO;
    const VkImageView layerView = views[views.size() - 2 + static_cast<size_t>(k)].get();
    colour[k].imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    colour[k].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    if (multisampled) {
      colour[k].imageView = (k == 0 ? msAlbedo_ : msNormal_).view.get();
      colour[k].resolveMode = VK_RESOLVE_MODE_AVERAGE_BIT;  // coverage → alpha
      colour[k].resolveImageView = layerView;
      colour[k].resolveImageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
      colour[k].storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    } else {
      colour[k].imageView = layerView;
      colour[k].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    }
    colour[k].clearValue.color = {{0.0f, 0.0f, 0.0f, 0.0f}};
  }
  VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  depth.imageView = depth_.view.get();
  depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
  depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  depth.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  depth.clearValue.depthStencil = {0.0f, 0};  // reverse-Z: far
  VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
  ri.renderArea = {{0, 0}, extent};
  ri.layerCount = 1;
  ri.colorAttachmentCount = 2;
  ri.pColorAttachments = colour;
  ri.pDepthAttachment = &depth;
  vkCmdBeginRendering(cmd, &ri);
  const VkViewport vp{0.0f, 0.0f, static_cast<float>(side), static_cast<float>(side), 0.0f, 1.0f};
  const VkRect2D scissor{{0, 0}, extent};
  vkCmdSetViewport(cmd, 0, 1, &vp);
  vkCmdSetScissor(cmd, 0, 1, &scissor);
  draw(cmd, layer);
  vkCmdEndRendering(cmd);
}

uint64_t TreeImpostors::pixelBytes(uint32_t layers) {
  uint64_t bytes = 0;
  for (uint32_t level = 0; level < kImpostorMipLevels; ++level) {
    const uint64_t side = (kImpostorViews * kImpostorCellPx) >> level;
    bytes += side * side * 4 * layers;
  }
  return 2 * bytes;
}

std::vector<std::pair<const GpuImage*, VkBufferImageCopy>> TreeImpostors::pixelRegions() const {
  std::vector<std::pair<const GpuImage*, VkBufferImageCopy>> regions;
  VkDeviceSize offset = 0;
  for (const GpuImage* img : {&albedo_, &normal_})
    for (uint32_t level = 0; level < kImpostorMipLevels; ++level) {
      const uint32_t side = img->extent.width >> level;
      VkBufferImageCopy r{};
      r.bufferOffset = offset;
      r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level, 0, img->layers};
      r.imageExtent = {side, side, 1};
      regions.emplace_back(img, r);
      offset += VkDeviceSize{side} * side * 4 * img->layers;
    }
  assert(offset == pixelBytes(albedo_.layers));
  return regions;
}

Result<std::unique_ptr<TreeImpostors>> TreeImpostors::fromPixels(const Context& ctx, uint32_t layers,
                                                                 const FillPixels& fill) {
  assert(layers > 0);
  const uint64_t bytes = pixelBytes(layers);
  GpuBuffer staging = createBuffer(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::HostUpload,
                                   "impostor upload");
  if (Status s = fill(std::span(static_cast<uint8_t*>(staging.mapped), bytes)); !s) return s.error();
  std::unique_ptr<TreeImpostors> t(new TreeImpostors(ctx));
  createAtlases(ctx, layers, t->albedo_, t->normal_);
  const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, kImpostorMipLevels, 0, layers};
  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    for (const GpuImage* img : {&t->albedo_, &t->normal_})
      transitionImageRange(cmd, img->get(), all, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                           VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    for (const auto& [img, region] : t->pixelRegions())
      vkCmdCopyBufferToImage(cmd, staging.get(), img->get(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    for (const GpuImage* img : {&t->albedo_, &t->normal_})
      transitionImageRange(cmd, img->get(), all, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                           VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT,
                           VK_ACCESS_2_TRANSFER_WRITE_BIT,
                           VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_COPY_BIT,
                           VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT);
  });
  return t;
}

void TreeImpostors::readPixels(const std::function<void(std::span<const uint8_t>)>& use) const {
  const uint64_t bytes = pixelBytes(albedo_.layers);
  GpuBuffer buffer = createBuffer(*ctx_, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::HostReadback,
                                  "impostor read-back");
  ctx_->submitAndWait([&](VkCommandBuffer cmd) {
    for (const auto& [img, r] : pixelRegions())
      recordSampledImageReadback(cmd, img->get(), r.imageSubresource, r.imageExtent, buffer, r.bufferOffset,
                                 VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT);
    hostReadBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  });
  use(std::span(static_cast<const uint8_t*>(buffer.mapped), bytes));
}

std::vector<uint8_t> TreeImpostors::readAlbedo(uint32_t layer, uint32_t level) const {
  assert(level < kImpostorMipLevels);
  const VkExtent2D e{albedo_.extent.width >> level, albedo_.extent.height >> level};
  const VkDeviceSize bytes = VkDeviceSize{e.width} * e.height * 4;
  GpuBuffer buffer = createBuffer(*ctx_, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::HostReadback,
                                  "impostor read-back");
  ctx_->submitAndWait([&](VkCommandBuffer cmd) {
    recordSampledImageReadback(cmd, albedo_.get(), {VK_IMAGE_ASPECT_COLOR_BIT, level, layer, 1}, {e.width, e.height, 1},
                               buffer, 0, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT);
    hostReadBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  });
  std::vector<uint8_t> out(static_cast<size_t>(bytes));
  std::memcpy(out.data(), buffer.mapped, out.size());
  return out;
}

}  // namespace vegstream::render
