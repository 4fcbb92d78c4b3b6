#include "render/detail_textures.h"

#include <cstring>

#include "render/descriptors.h"
#include "render/detail_patterns.h"

namespace vegstream::render {

DetailTextures::DetailTextures(const Context& ctx, std::span<const vegetation::TerrainType> types,
                               const DetailSettings& settings)
    : ctx_(&ctx), settings_(settings) {
  const VkDescriptorSetLayoutBinding bindings[] = {
      {0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT | VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
      {1, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, VK_SHADER_STAGE_FRAGMENT_BIT | VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
  };
  layout_ = createLayout(ctx, bindings, "terrain detail layout");
  const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1},
                                        {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1}};
  pool_ = createPool(ctx, sizes, 1, "terrain detail pool");
  set_ = allocateDescriptorSet(ctx, pool_.get(), layout_.get(), "terrain detail set");

  const uint32_t mips = mipLevelCount(kDetailTextureSize);
  image_ = createImageArray(ctx, {kDetailTextureSize, kDetailTextureSize}, vegetation::kDetailSurfaceCount,
                            VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                            "terrain detail textures", mips);
  sampler_ = createLinearRepeatSampler(ctx, mips, "terrain detail sampler");

  const std::vector<uint8_t>& texels = detailTextureData();
  GpuBuffer staging = createBuffer(ctx, texels.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::HostUpload,
                                   "terrain detail staging");
  std::memcpy(staging.mapped, texels.data(), texels.size());
  ctx.submitAndWait([&](VkCommandBuffer cmd) { recordImageArrayUpload(cmd, staging, image_); });

  const TerrainDetailUniforms block = packTerrainDetail(types, settings);
  uniforms_ =
      createBufferWithData(ctx, &block, sizeof(block), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, "terrain detail uniforms");
  writeSampledImage(ctx, set_, sampler_.get(), image_.view.get(), 0);
  writeUniformBuffer(ctx, set_, uniforms_.get(), sizeof(block), 1);
}

void DetailTextures::setTypes(std::span<const vegetation::TerrainType> types) {
  const TerrainDetailUniforms block = packTerrainDetail(types, settings_);
  uniforms_ = createBufferWithData(*ctx_, &block, sizeof(block), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                                   "terrain detail uniforms");
  writeUniformBuffer(*ctx_, set_, uniforms_.get(), sizeof(block), 1);
}

}  // namespace vegstream::render
