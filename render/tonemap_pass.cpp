#include "render/tonemap_pass.h"

#include <cstring>

#include "render/descriptors.h"
#include "render/pipeline_builder.h"
#include "shaders/exposure_histogram.comp.h"
#include "shaders/exposure_resolve.comp.h"
#include "shaders/tonemap.comp.h"

namespace vegstream::render {
namespace {
constexpr VkDeviceSize kStateBytes = kExposureBins * 4 + 16;  // ExposureState in std430
constexpr VkDeviceSize kBinBytes = kExposureBins * 4;
constexpr VkPipelineStageFlags2 kCompute = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
constexpr VkAccessFlags2 kStorageRW = VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;

uint32_t groups(uint32_t n, uint32_t size) { return (n + size - 1) / size; }
}  // namespace

TonemapPass::TonemapPass(const Context& ctx, const RenderTargets& targets) {
  const VkShaderStageFlags c = VK_SHADER_STAGE_COMPUTE_BIT;
  const VkDescriptorSetLayoutBinding bindings[] = {
      {0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, c, nullptr},   // the resolved HDR colour
      {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, c, nullptr},  // ExposureState
      {2, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, c, nullptr},   // the display target (as UNORM)
      {3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, c, nullptr},  // per-slot EV read-back
  };
  setLayout_ = createLayout(ctx, bindings, "tonemap layout");
  const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 2}, {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 2}};
  pool_ = createPool(ctx, sizes, 1, "tonemap pool");
  set_ = allocateDescriptorSet(ctx, pool_.get(), setLayout_.get(), "tonemap set");
  state_ = createBuffer(ctx, kStateBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                        MemoryUse::DeviceLocal, "exposure state");
  readback_ = createBuffer(ctx, sizeof(float) * kFramesInFlight, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                           MemoryUse::HostReadback, "exposure read-back");
  std::memset(readback_.mapped, 0, sizeof(float) * kFramesInFlight);
  writeStorageImage(ctx, set_, targets.color().view.get(), 0);
  writeStorageBuffer(ctx, set_, state_.get(), 1);
  writeStorageImage(ctx, set_, targets.display().alternateView.get(), 2);
  writeStorageBuffer(ctx, set_, readback_.get(), 3);
  const VkPushConstantRange push{c, 0, sizeof(TonemapPush)};
  const VkDescriptorSetLayout sets[] = {setLayout_.get()};
  layout_ = createPipelineLayout(ctx, sets, {&push, 1}, "tonemap pipeline layout");
  histogram_ = createComputePipeline(ctx, layout_.get(), spv_exposure_histogram_comp, "exposure histogram");
  resolve_ = createComputePipeline(ctx, layout_.get(), spv_exposure_resolve_comp, "exposure resolve");
  tonemap_ = createComputePipeline(ctx, layout_.get(), spv_tonemap_comp, "tonemap");
}

void TonemapPass::record(VkCommandBuffer cmd, int slot, const ToneSettings& s, const RenderTargets& targets) const {
  const VkExtent2D e = targets.extent();
  const GpuImage& hdr = targets.color();
  const GpuImage& display = targets.display();
  transitionImage(cmd, hdr.get(), hdr.aspect, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL,
                  VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, kCompute,
                  VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
  transitionImage(cmd, display.get(), display.aspect, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                  VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0, kCompute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  // The bins start at zero each frame, after the last frame's resolve read them.
  memoryBarrier(cmd, kCompute, kStorageRW, VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  vkCmdFillBuffer(cmd, state_.get(), 0, kBinBytes, 0);
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, kCompute, kStorageRW);

  const TonemapPush push{glm::vec4(float(static_cast<uint32_t>(s.mode)), s.fixedEv, s.adapt ? 1.0f : 0.0f,
                                   s.frameSeconds),
                         glm::uvec4(uint32_t(slot), e.width, e.height, 0u)};
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.get(), 0, 1, &set_, 0, nullptr);
  vkCmdPushConstants(cmd, layout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
  if (s.mode == ToneMode::Auto) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, histogram_.get());
    vkCmdDispatch(cmd, groups(e.width, 16), groups(e.height, 16), 1);
    memoryBarrier(cmd, kCompute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, kCompute, kStorageRW);
  }
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, resolve_.get());
  vkCmdDispatch(cmd, 1, 1, 1);
  memoryBarrier(cmd, kCompute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, kCompute | VK_PIPELINE_STAGE_2_HOST_BIT,
                VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_HOST_READ_BIT);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, tonemap_.get());
  vkCmdDispatch(cmd, groups(e.width, 8), groups(e.height, 8), 1);
  // The HUD draws over it, the read-back and the present blit copy it.
  transitionImage(cmd, display.get(), display.aspect, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                  kCompute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_2_COPY_BIT |
                      VK_PIPELINE_STAGE_2_BLIT_BIT,
                  VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT |
                      VK_ACCESS_2_TRANSFER_READ_BIT);
}

float TonemapPass::exposureEv(int slot) const { return static_cast<const float*>(readback_.mapped)[slot]; }

}  // namespace vegstream::render
