#pragma once
// Descriptor plumbing shared by the passes. Most sets vegstream uses have exactly one binding
// (binding 0): a uniform buffer for the frame, a combined image sampler for a texture; the
// terrain detail set has two (textures + terrain-type table). These helpers create, name and
// write such sets so each pass states only what differs.

#include <span>
#include <string>

#include "render/context.h"
#include "render/handle.h"

namespace vegstream::render {

// A layout with the given bindings.
DescriptorSetLayout createLayout(const Context& ctx, std::span<const VkDescriptorSetLayoutBinding> bindings,
                                 const std::string& name);

// A pool for `maxSets` sets holding the descriptors of `sizes` in all.
DescriptorPool createPool(const Context& ctx, std::span<const VkDescriptorPoolSize> sizes, uint32_t maxSets,
                          const std::string& name);

// A layout with one descriptor of `type` at binding 0, visible to `stages`.
DescriptorSetLayout createSingleBindingLayout(const Context& ctx, VkDescriptorType type, VkShaderStageFlags stages,
                                              const std::string& name);

// A pool for `maxSets` sets of the single-binding layout above.
DescriptorPool createSingleBindingPool(const Context& ctx, VkDescriptorType type, uint32_t maxSets,
                                       const std::string& name);

// One set from `pool`; freed with the pool.
VkDescriptorSet allocateDescriptorSet(const Context& ctx, VkDescriptorPool pool, VkDescriptorSetLayout layout,
                                      const std::string& name);
// One set per frame slot (sets[i] for slot i) from `pool`, named "<name> (slot i)"; freed with
// the pool.
void allocateSlotSets(const Context& ctx, VkDescriptorPool pool, VkDescriptorSetLayout layout,
                      std::span<VkDescriptorSet> sets, const std::string& name);

// `binding` := the image view, sampled in SHADER_READ_ONLY_OPTIMAL. The caller guarantees no
// pending GPU work reads the set (Vulkan forbids updating a set in use).
void writeSampledImage(const Context& ctx, VkDescriptorSet set, VkSampler sampler, VkImageView view,
                       uint32_t binding = 0);

// `binding` := the image view as a separate sampled image (no sampler of its own), in
// SHADER_READ_ONLY_OPTIMAL.
void writeSeparateImage(const Context& ctx, VkDescriptorSet set, VkImageView view, uint32_t binding);

// `binding` := the first `range` bytes of a uniform buffer.
void writeUniformBuffer(const Context& ctx, VkDescriptorSet set, VkBuffer buffer, VkDeviceSize range,
                        uint32_t binding = 0);

// `binding` := a storage image view, accessed in GENERAL layout.
void writeStorageImage(const Context& ctx, VkDescriptorSet set, VkImageView view, uint32_t binding);

// `binding` := a whole storage buffer.
void writeStorageBuffer(const Context& ctx, VkDescriptorSet set, VkBuffer buffer, uint32_t binding);

// Bilinear, clamped, no mip levels: what the terrain imagery and the HUD atlas both want.
Sampler createLinearClampSampler(const Context& ctx, const std::string& name);
// Bilinear within a level, linear between `mipLevels` levels, clamped (the impostor atlases).
Sampler createTrilinearClampSampler(const Context& ctx, uint32_t mipLevels, const std::string& name);

// Nearest, clamped, one level: texelFetch reads (exact texels, integer-encoded data).
Sampler createNearestClampSampler(const Context& ctx, const std::string& name);

// Trilinear, repeating, all `mipLevels` levels: tiling textures (terrain detail).
Sampler createLinearRepeatSampler(const Context& ctx, uint32_t mipLevels, const std::string& name);

}  // namespace vegstream::render
