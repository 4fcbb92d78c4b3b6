#include "render/descriptors.h"

#include "render/create_named.h"

namespace vegstream::render {

DescriptorSetLayout createLayout(const Context& ctx, std::span<const VkDescriptorSetLayoutBinding> bindings,
                                 const std::string& name) {
  VkDescriptorSetLayoutCreateInfo lci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  lci.bindingCount = static_cast<uint32_t>(bindings.size());
  lci.pBindings = bindings.data();
  return createNamed<DescriptorSetLayout>(ctx, VK_OBJECT_TYPE_DESCRIPTOR_SET_LAYOUT, name,
                                          "vkCreateDescriptorSetLayout", vkCreateDescriptorSetLayout, lci);
}

DescriptorSetLayout createSingleBindingLayout(const Context& ctx, VkDescriptorType type, VkShaderStageFlags stages,
                                              const std::string& name) {
  const VkDescriptorSetLayoutBinding binding{0, type, 1, stages, nullptr};
  return createLayout(ctx, {&binding, 1}, name);
}

DescriptorPool createPool(const Context& ctx, std::span<const VkDescriptorPoolSize> sizes, uint32_t maxSets,
                          const std::string& name) {
  VkDescriptorPoolCreateInfo pci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pci.maxSets = maxSets;
  pci.poolSizeCount = static_cast<uint32_t>(sizes.size());
  pci.pPoolSizes = sizes.data();
  return createNamed<DescriptorPool>(ctx, VK_OBJECT_TYPE_DESCRIPTOR_POOL, name, "vkCreateDescriptorPool",
                                     vkCreateDescriptorPool, pci);
}

DescriptorPool createSingleBindingPool(const Context& ctx, VkDescriptorType type, uint32_t maxSets,
                                       const std::string& name) {
  const VkDescriptorPoolSize poolSize{type, maxSets};
  return createPool(ctx, {&poolSize, 1}, maxSets, name);
}

VkDescriptorSet allocateDescriptorSet(const Context& ctx, VkDescriptorPool pool, VkDescriptorSetLayout layout,
                                      const std::string& name) {
  VkDescriptorSetAllocateInfo dai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  dai.descriptorPool = pool;
  dai.descriptorSetCount = 1;
  dai.pSetLayouts = &layout;
  VkDescriptorSet set;
  vkCheck(vkAllocateDescriptorSets(ctx.device(), &dai, &set), "vkAllocateDescriptorSets");
  ctx.setName(VK_OBJECT_TYPE_DESCRIPTOR_SET, set, name);
  return set;
}

void allocateSlotSets(const Context& ctx, VkDescriptorPool pool, VkDescriptorSetLayout layout,
                      std::span<VkDescriptorSet> sets, const std::string& name) {
  for (size_t i = 0; i < sets.size(); ++i)
    sets[i] = allocateDescriptorSet(ctx, pool, layout, name + " (slot " + std::to_string(i) + ")");
}

namespace {
// `binding` := one descriptor of `type`: the image or the buffer given (the other null).
void writeDescriptor(const Context& ctx, VkDescriptorSet set, uint32_t binding, VkDescriptorType type,
                     const VkDescriptorImageInfo* image, const VkDescriptorBufferInfo* buffer) {
  VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  w.dstSet = set;
  w.dstBinding = binding;
  w.descriptorCount = 1;
  w.descriptorType = type;
  w.pImageInfo = image;
  w.pBufferInfo = buffer;
  vkUpdateDescriptorSets(ctx.device(), 1, &w, 0, nullptr);
}

void writeImage(const Context& ctx, VkDescriptorSet set, VkDescriptorType type, const VkDescriptorImageInfo& image,
                uint32_t binding) {
  writeDescriptor(ctx, set, binding, type, &image, nullptr);
}

void writeBuffer(const Context& ctx, VkDescriptorSet set, VkDescriptorType type, VkBuffer buffer, VkDeviceSize range,
                 uint32_t binding) {
  const VkDescriptorBufferInfo bi{buffer, 0, range};
  writeDescriptor(ctx, set, binding, type, nullptr, &bi);
}
}  // namespace

void writeSampledImage(const Context& ctx, VkDescriptorSet set, VkSampler sampler, VkImageView view, uint32_t binding) {
  writeImage(ctx, set, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
             {sampler, view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}, binding);
}

void writeSeparateImage(const Context& ctx, VkDescriptorSet set, VkImageView view, uint32_t binding) {
  writeImage(ctx, set, VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE,
             {VK_NULL_HANDLE, view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}, binding);
}

void writeUniformBuffer(const Context& ctx, VkDescriptorSet set, VkBuffer buffer, VkDeviceSize range,
                        uint32_t binding) {
  writeBuffer(ctx, set, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, buffer, range, binding);
}

void writeStorageImage(const Context& ctx, VkDescriptorSet set, VkImageView view, uint32_t binding) {
  writeImage(ctx, set, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, {VK_NULL_HANDLE, view, VK_IMAGE_LAYOUT_GENERAL}, binding);
}

void writeStorageBuffer(const Context& ctx, VkDescriptorSet set, VkBuffer buffer, uint32_t binding) {
  writeBuffer(ctx, set, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, buffer, VK_WHOLE_SIZE, binding);
}

namespace {
// The one place samplers are made: `filter` within a level, `mipmap` between levels (maxLod 0:
// level 0 only), `address` at the edges.
Sampler createSampler(const Context& ctx, VkFilter filter, VkSamplerMipmapMode mipmap, VkSamplerAddressMode address,
                      float maxLod, const std::string& name) {
  VkSamplerCreateInfo sci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  sci.magFilter = filter;
  sci.minFilter = filter;
  sci.mipmapMode = mipmap;
  sci.addressModeU = sci.addressModeV = sci.addressModeW = address;
  sci.maxLod = maxLod;
  return createNamed<Sampler>(ctx, VK_OBJECT_TYPE_SAMPLER, name, "vkCreateSampler", vkCreateSampler, sci);
}
}  // namespace

Sampler createNearestClampSampler(const Context& ctx, const std::string& name) {
  return createSampler(ctx, VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
                       0.0f, name);
}

Sampler createLinearClampSampler(const Context& ctx, const std::string& name) {
  return createSampler(ctx, VK_FILTER_LINEAR, VK_SAMPLER_MIPMAP_MODE_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
                       0.0f, name);
}

Sampler createTrilinearClampSampler(const Context& ctx, uint32_t mipLevels, const std::string& name) {
  return createSampler(ctx, VK_FILTER_LINEAR, VK_SAMPLER_MIPMAP_MODE_LINEAR, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
                       static_cast<float>(mipLevels), name);
}

Sampler createLinearRepeatSampler(const Context& ctx, uint32_t mipLevels, const std::string& name) {
  return createSampler(ctx, VK_FILTER_LINEAR, VK_SAMPLER_MIPMAP_MODE_LINEAR, VK_SAMPLER_ADDRESS_MODE_REPEAT,
                       static_cast<float>(mipLevels), name);
}

}  // namespace vegstream::render
