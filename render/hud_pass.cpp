// The HUD overlay (hud_pass.h): the overlay's draw data, its atlas uploaded when it changes, drawn
// over the tone-mapped display target.
#include "render/hud_pass.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "render/descriptors.h"
#include "render/pipeline_builder.h"
#include "render/render_targets.h"
#include "render/vk_check.h"
#include "shaders/hud.frag.h"
#include "shaders/hud.vert.h"

namespace vegstream::render {
namespace {
struct HudPush {
  float scale[2];
  float translate[2];
};

// Rendering into the display target, over what the scene drew there.
void beginOverlayRendering(VkCommandBuffer cmd, const GpuImage& target) {
  // The scene's rendering (and its MSAA resolve) wrote the target; the overlay reads and
  // blends over it.
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);

  VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  color.imageView = target.view.get();
  color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
  color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
  ri.renderArea = {{0, 0}, target.extent};
  ri.layerCount = 1;
  ri.colorAttachmentCount = 1;
  ri.pColorAttachments = &color;
  vkCmdBeginRendering(cmd, &ri);
}

// The overlay's draw commands, each in its clip rectangle (a bad command is skipped); returns the
// triangles drawn.
uint64_t drawCommands(VkCommandBuffer cmd, const OverlayDrawData& data, VkExtent2D extent) {
  // Clip rectangles are in layout pixels; scale them to the target.
  const float sx = static_cast<float>(extent.width) / data.width;
  const float sy = static_cast<float>(extent.height) / data.height;
  const auto clampTo = [](float v, uint32_t limit) {
    return static_cast<int32_t>(std::clamp(v, 0.0f, static_cast<float>(limit)));
  };
  uint64_t triangles = 0;
  const auto indexCount = static_cast<uint32_t>(data.indices.size());
  const auto vertexCount = static_cast<int64_t>(data.vertices.size());
  for (const OverlayCommand& c : data.commands) {
    if (c.indexCount == 0 || c.firstIndex > indexCount || c.indexCount > indexCount - c.firstIndex) continue;
    if (c.vertexOffset < 0 || c.vertexOffset >= vertexCount) continue;
    const int32_t x0 = clampTo(std::floor(c.clipX0 * sx), extent.width);
    const int32_t y0 = clampTo(std::floor(c.clipY0 * sy), extent.height);
    const int32_t x1 = clampTo(std::ceil(c.clipX1 * sx), extent.width);
    const int32_t y1 = clampTo(std::ceil(c.clipY1 * sy), extent.height);
    if (x1 <= x0 || y1 <= y0) continue;
    const VkRect2D scissor{{x0, y0}, {static_cast<uint32_t>(x1 - x0), static_cast<uint32_t>(y1 - y0)}};
    vkCmdSetScissor(cmd, 0, 1, &scissor);
    vkCmdDrawIndexed(cmd, c.indexCount, 1, c.firstIndex, c.vertexOffset, 0);
    triangles += c.indexCount / 3;
  }
  return triangles;
}

}  // namespace

HudPass::HudPass(const Context& ctx) : ctx_(&ctx) {
  setLayout_ = createSingleBindingLayout(ctx, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT,
                                         "hud atlas layout");
  pool_ = createSingleBindingPool(ctx, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, kSlots, "hud descriptor pool");
  allocateSlotSets(ctx, pool_.get(), setLayout_.get(), sets_, "hud atlas set");
  sampler_ = createLinearClampSampler(ctx, "hud atlas sampler");
  const VkDescriptorSetLayout setLayout = setLayout_.get();

  const VkPushConstantRange push{VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(HudPush)};
  layout_ = createPipelineLayout(ctx, {&setLayout, 1}, {&push, 1}, "hud pipeline layout");
  GraphicsPipelineDesc desc;
  desc.name = "hud pipeline";
  desc.stages = {{VK_SHADER_STAGE_VERTEX_BIT, spv_hud_vert}, {VK_SHADER_STAGE_FRAGMENT_BIT, spv_hud_frag}};
  desc.bindings = {{0, sizeof(OverlayVertex), VK_VERTEX_INPUT_RATE_VERTEX}};
  desc.attributes = {
      {0, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(OverlayVertex, x)},
      {1, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(OverlayVertex, u)},
      {2, 0, VK_FORMAT_R8G8B8A8_UNORM, offsetof(OverlayVertex, rgba)},
  };
  desc.cullMode = VK_CULL_MODE_NONE;  // ImGui emits both windings
  desc.depthTest = false;
  desc.depthWrite = false;
  desc.alphaBlend = true;
  desc.samples = VK_SAMPLE_COUNT_1_BIT;
  desc.colorFormat = kDisplayFormat;  // over the tone-mapped display target
  desc.depthFormat = VK_FORMAT_UNDEFINED;
  desc.layout = layout_.get();
  pipeline_ = createGraphicsPipeline(ctx, desc);
}

void HudPass::uploadTexture(VkCommandBuffer cmd, const OverlayImage& image,
                            const std::function<void(GpuBuffer&&)>& retireBuffer,
                            const std::function<void(GpuImage&&)>& retireImage) {
  const VkDeviceSize bytes = VkDeviceSize{image.width} * image.height * 4;
  GpuBuffer staging =
      createBuffer(*ctx_, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::HostUpload, "hud atlas staging");
  std::memcpy(staging.mapped, image.rgba.data(), static_cast<size_t>(bytes));
  if (texture_.image) retireImage(std::move(texture_));
  texture_ =
      createImage2D(*ctx_, {image.width, image.height}, VK_FORMAT_R8G8B8A8_UNORM,
                    VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, VK_SAMPLE_COUNT_1_BIT, "hud atlas");
  recordImageUpload(cmd, staging, texture_);
  retireBuffer(std::move(staging));  // the copy runs with this frame
  textureId_ = image.id;
}

void HudPass::ensureCapacity(GpuBuffer& buffer, VkDeviceSize bytes, VkBufferUsageFlags usage, const char* what,
                             int slot, const std::function<void(GpuBuffer&&)>& retire) {
  if (buffer.buffer && buffer.size >= bytes) return;
  if (buffer.buffer) retire(std::move(buffer));
  buffer = createBuffer(*ctx_, grownSize(bytes), usage, MemoryUse::HostUpload,
                        std::string("hud ") + what + " (slot " + std::to_string(slot) + ")");
}

uint64_t HudPass::record(VkCommandBuffer cmd, int slot, const OverlayDrawData& data, const GpuImage& target,
                         const std::function<void(GpuBuffer&&)>& retireBuffer,
                         const std::function<void(GpuImage&&)>& retireImage) {
  if (data.commands.empty() || data.vertices.empty() || data.indices.empty() || !data.texture) return 0;
  if (data.width <= 0.0f || data.height <= 0.0f) return 0;
  const OverlayImage& image = *data.texture;
  if (image.width == 0 || image.height == 0 || image.rgba.size() != size_t{image.width} * image.height * 4) return 0;
  // Uploads are recorded outside rendering, into this frame's commands.
  if (image.id != textureId_) uploadTexture(cmd, image, retireBuffer, retireImage);
  const auto s = static_cast<size_t>(slot);
  if (setTextureId_[s] != textureId_) {
    // Only this slot's frames use this set, and the slot's previous frame has completed.
    writeSampledImage(*ctx_, sets_[s], sampler_.get(), texture_.view.get());
    setTextureId_[s] = textureId_;
  }
  const VkDeviceSize vbytes = data.vertices.size() * sizeof(OverlayVertex);
  const VkDeviceSize ibytes = data.indices.size() * sizeof(uint32_t);
  ensureCapacity(vertices_[s], vbytes, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, "vertices", slot, retireBuffer);
  ensureCapacity(indices_[s], ibytes, VK_BUFFER_USAGE_INDEX_BUFFER_BIT, "indices", slot, retireBuffer);
  std::memcpy(vertices_[s].mapped, data.vertices.data(), static_cast<size_t>(vbytes));
  std::memcpy(indices_[s].mapped, data.indices.data(), static_cast<size_t>(ibytes));

  beginOverlayRendering(cmd, target);
  const VkExtent2D extent = target.extent;
  const VkViewport viewport{0.0f, 0.0f, static_cast<float>(extent.width), static_cast<float>(extent.height),
                            0.0f, 1.0f};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_.get());
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_.get(), 0, 1, &sets_[s], 0, nullptr);
  const HudPush push{{2.0f / data.width, 2.0f / data.height}, {-1.0f, -1.0f}};
  vkCmdPushConstants(cmd, layout_.get(), VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(push), &push);
  const VkBuffer vb = vertices_[s].get();
  const VkDeviceSize offset = 0;
  vkCmdBindVertexBuffers(cmd, 0, 1, &vb, &offset);
  vkCmdBindIndexBuffer(cmd, indices_[s].get(), 0, VK_INDEX_TYPE_UINT32);

  const uint64_t triangles = drawCommands(cmd, data, extent);
  vkCmdEndRendering(cmd);
  return triangles;
}

}  // namespace vegstream::render
