#include "render/atmosphere_pass.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <glm/gtc/packing.hpp>

#include "render/descriptors.h"
#include "render/pipeline_builder.h"
#include "render/vk_check.h"
#include "shaders/atmosphere_multiscatter.comp.h"
#include "shaders/atmosphere_sky_light.comp.h"
#include "shaders/atmosphere_transmittance.comp.h"
#include "shaders/atmosphere_view.comp.h"

namespace vegstream::render {
namespace {
constexpr VkFormat kLutFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
constexpr double kBottomRadiusKm = 6360.0;  // = atmosphere_model.glsl's
constexpr VkDeviceSize kSkyLightBytes = 4 * 16;
constexpr VkPipelineStageFlags2 kCompute = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
constexpr VkPipelineStageFlags2 kReaders = VK_PIPELINE_STAGE_2_ALL_GRAPHICS_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;

uint32_t groups(uint32_t n) { return (n + 7) / 8; }

// A LUT's contents are rewritten: whatever read it before (an earlier frame) first.
void toWritable(VkCommandBuffer cmd, const GpuImage& lut, bool firstUse) {
  transitionImage(cmd, lut.get(), lut.aspect, firstUse ? VK_IMAGE_LAYOUT_UNDEFINED : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                  VK_IMAGE_LAYOUT_GENERAL, kReaders, 0, kCompute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
}
void toReadable(VkCommandBuffer cmd, const GpuImage& lut) {
  transitionImage(cmd, lut.get(), lut.aspect, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                  kCompute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, kReaders, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
}
}  // namespace

float atmosphereCameraRadiusKm(double heightMslM) {
  return static_cast<float>(kBottomRadiusKm + std::max(heightMslM * 1e-3, 0.001));
}

AtmospherePass::AtmospherePass(const Context& ctx) : ctx_(&ctx) {
  const VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                                  VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  transmittance_ = createImage2D(ctx, kTransmittanceLutSize, kLutFormat, usage, VK_SAMPLE_COUNT_1_BIT, "transmittance LUT");
  multiScattering_ =
      createImage2D(ctx, kMultiScatteringLutSize, kLutFormat, usage, VK_SAMPLE_COUNT_1_BIT, "multiple-scattering LUT");
  skyView_ = createImage2D(ctx, kSkyViewLutSize, kLutFormat, usage, VK_SAMPLE_COUNT_1_BIT, "sky-view LUT");
  aerial_ = createImage3D(ctx, {kAerialLutSize[0], kAerialLutSize[1]}, kAerialLutSize[2], kLutFormat, usage,
                          "aerial-perspective volume");
  skyLight_ = createBuffer(ctx, kSkyLightBytes,
                           VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                           MemoryUse::DeviceLocal, "sky light");
  linear_ = createLinearClampSampler(ctx, "atmosphere LUT sampler");

  const VkShaderStageFlags c = VK_SHADER_STAGE_COMPUTE_BIT;
  const VkDescriptorSetLayoutBinding bindings[] = {
      {0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, c, nullptr}, {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, c, nullptr},
      {2, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, c, nullptr},          {3, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, c, nullptr},
      {4, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, c, nullptr},          {5, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, c, nullptr},
      {6, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, c, nullptr}, {7, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, c, nullptr}};
  setLayout_ = createLayout(ctx, bindings, "atmosphere layout");
  const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 3},
                                        {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 4},
                                        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1}};
  pool_ = createPool(ctx, sizes, 1, "atmosphere pool");
  set_ = allocateDescriptorSet(ctx, pool_.get(), setLayout_.get(), "atmosphere set");
  writeSampledImage(ctx, set_, linear_.get(), transmittance_.view.get(), 0);
  writeSampledImage(ctx, set_, linear_.get(), multiScattering_.view.get(), 1);
  writeStorageImage(ctx, set_, transmittance_.view.get(), 2);
  writeStorageImage(ctx, set_, multiScattering_.view.get(), 3);
  writeStorageImage(ctx, set_, skyView_.view.get(), 4);
  writeStorageImage(ctx, set_, aerial_.view.get(), 5);
  writeSampledImage(ctx, set_, linear_.get(), skyView_.view.get(), 6);
  writeStorageBuffer(ctx, set_, skyLight_.get(), 7);
  const VkPushConstantRange push{c, 0, sizeof(AtmospherePush)};
  const VkDescriptorSetLayout sets[] = {setLayout_.get()};
  layout_ = createPipelineLayout(ctx, sets, {&push, 1}, "atmosphere pipeline layout");
  transmittancePipe_ = createComputePipeline(ctx, layout_.get(), spv_atmosphere_transmittance_comp, "transmittance LUT");
  multiScatteringPipe_ =
      createComputePipeline(ctx, layout_.get(), spv_atmosphere_multiscatter_comp, "multiple-scattering LUT");
  viewPipe_ = createComputePipeline(ctx, layout_.get(), spv_atmosphere_view_comp, "sky-view and aerial LUTs");
  skyLightPipe_ = createComputePipeline(ctx, layout_.get(), spv_atmosphere_sky_light_comp, "sky light");
  // The atmosphere's own LUTs now; the frame's LUTs zeroed and readable, so anything that binds
  // set 0 before the first frame (the trees' impostor capture) finds them valid.
  ctx.submitAndWait([&](VkCommandBuffer cmd) { recordStaticLuts(cmd); });
}

void AtmospherePass::recordStaticLuts(VkCommandBuffer cmd) const {
  const AtmospherePush push{glm::vec4(atmosphereCameraRadiusKm(0.0), 1.0f, kAerialFarKm, 1.0f)};
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.get(), 0, 1, &set_, 0, nullptr);
  vkCmdPushConstants(cmd, layout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
  toWritable(cmd, transmittance_, true);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, transmittancePipe_.get());
  vkCmdDispatch(cmd, groups(kTransmittanceLutSize.width), groups(kTransmittanceLutSize.height), 1);
  toReadable(cmd, transmittance_);
  toWritable(cmd, multiScattering_, true);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, multiScatteringPipe_.get());
  vkCmdDispatch(cmd, groups(kMultiScatteringLutSize.width), groups(kMultiScatteringLutSize.height), 1);
  toReadable(cmd, multiScattering_);
  const VkClearColorValue zero{};
  const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  for (const GpuImage* lut : {&skyView_, &aerial_}) {
    transitionImage(cmd, lut->get(), lut->aspect, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                    VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0, VK_PIPELINE_STAGE_2_CLEAR_BIT,
                    VK_ACCESS_2_TRANSFER_WRITE_BIT);
    vkCmdClearColorImage(cmd, lut->get(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero, 1, &all);
    transitionImage(cmd, lut->get(), lut->aspect, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                    VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_CLEAR_BIT,
                    VK_ACCESS_2_TRANSFER_WRITE_BIT, kReaders, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  }
  vkCmdFillBuffer(cmd, skyLight_.get(), 0, kSkyLightBytes, 0);
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, kReaders,
                VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
}

void AtmospherePass::record(VkCommandBuffer cmd, double cameraHeightMslM, const glm::vec3& sunDirection,
                            bool multipleScattering) const {
  const AtmospherePush push{glm::vec4(atmosphereCameraRadiusKm(cameraHeightMslM), std::clamp(sunDirection.z, -1.0f, 1.0f),
                                      kAerialFarKm, multipleScattering ? 1.0f : 0.0f)};
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.get(), 0, 1, &set_, 0, nullptr);
  vkCmdPushConstants(cmd, layout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
  toWritable(cmd, skyView_, false);
  toWritable(cmd, aerial_, false);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, viewPipe_.get());
  vkCmdDispatch(cmd, groups(std::max(kSkyViewLutSize.width, kAerialLutSize[0])),
                groups(std::max(kSkyViewLutSize.height, kAerialLutSize[1])), 2);
  toReadable(cmd, skyView_);
  toReadable(cmd, aerial_);
  // The sky light's buffer: the last frame's readers first, then this frame's readers after it.
  memoryBarrier(cmd, kReaders, VK_ACCESS_2_SHADER_STORAGE_READ_BIT, kCompute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, skyLightPipe_.get());
  vkCmdDispatch(cmd, 1, 1, 1);
  memoryBarrier(cmd, kCompute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, kReaders | VK_PIPELINE_STAGE_2_COPY_BIT,
                VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT);
}

void AtmospherePass::writeFrameSet(VkDescriptorSet set) const {
  writeSampledImage(*ctx_, set, linear_.get(), skyView_.view.get(), 7);
  writeSampledImage(*ctx_, set, linear_.get(), aerial_.view.get(), 8);
  writeStorageBuffer(*ctx_, set, skyLight_.get(), 9);
}

namespace {
// A LUT (SHADER_READ_ONLY_OPTIMAL) into `host` at `offset`, and back.
void copyLut(VkCommandBuffer cmd, const GpuImage& lut, const GpuBuffer& host, VkDeviceSize offset) {
  recordSampledImageReadback(cmd, lut.get(), {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                             {lut.extent.width, lut.extent.height, lut.depth}, host, offset, kReaders);
}

VkDeviceSize lutBytes(const GpuImage& lut) { return VkDeviceSize{lut.extent.width} * lut.extent.height * lut.depth * 8; }

LutImage unpackLut(const GpuImage& lut, const uint8_t* bytes) {
  LutImage out{lut.extent.width, lut.extent.height, lut.depth, {}};
  out.texels.resize(size_t{out.width} * out.height * out.depth);
  for (size_t i = 0; i < out.texels.size(); ++i) {
    uint16_t h[4];
    std::memcpy(h, bytes + i * 8, 8);
    out.texels[i] = glm::vec4(glm::unpackHalf1x16(h[0]), glm::unpackHalf1x16(h[1]), glm::unpackHalf1x16(h[2]),
                              glm::unpackHalf1x16(h[3]));
  }
  return out;
}
}  // namespace

AtmosphereLuts AtmospherePass::readBack() const {
  vkCheck(vkDeviceWaitIdle(ctx_->device()), "vkDeviceWaitIdle");
  const GpuImage* luts[] = {&transmittance_, &multiScattering_, &skyView_, &aerial_};
  VkDeviceSize offsets[5] = {0};
  for (int i = 0; i < 4; ++i) offsets[i + 1] = offsets[i] + lutBytes(*luts[i]);
  GpuBuffer host = createBuffer(*ctx_, offsets[4] + kSkyLightBytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                MemoryUse::HostReadback, "atmosphere read-back");
  ctx_->submitAndWait([&](VkCommandBuffer cmd) {
    for (int i = 0; i < 4; ++i) copyLut(cmd, *luts[i], host, offsets[i]);
    const VkBufferCopy light{0, offsets[4], kSkyLightBytes};
    vkCmdCopyBuffer(cmd, skyLight_.get(), host.get(), 1, &light);
    hostReadBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  });
  const auto* bytes = static_cast<const uint8_t*>(host.mapped);
  AtmosphereLuts out;
  out.transmittance = unpackLut(transmittance_, bytes + offsets[0]);
  out.multiScattering = unpackLut(multiScattering_, bytes + offsets[1]);
  out.skyView = unpackLut(skyView_, bytes + offsets[2]);
  out.aerial = unpackLut(aerial_, bytes + offsets[3]);
  std::memcpy(out.skyLight.data(), bytes + offsets[4], kSkyLightBytes);
  return out;
}

}  // namespace vegstream::render
