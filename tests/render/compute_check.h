#pragma once
// One compute kernel run once, for the tests that compare GLSL with its C++ reference
// (colour scores, Philox, plant roots): the buffers bound in set 0 at the given bindings, push
// constants, `threads` invocations in workgroups of 64, then a barrier so the host can read the
// results. Validation is whatever the context has (the GpuTest fixture's: on).

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "render/context.h"
#include "render/descriptors.h"
#include "render/gpu_resources.h"
#include "render/pipeline_builder.h"

namespace vegstream::render::testing {

struct CheckBinding {
  uint32_t binding = 0;
  VkDescriptorType type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;  // or UNIFORM_BUFFER
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceSize range = VK_WHOLE_SIZE;
};

inline void runComputeCheck(const Context& ctx, std::span<const uint32_t> spirv, std::span<const CheckBinding> bindings,
                            std::span<const std::byte> push, uint32_t threads, const std::string& name) {
  std::vector<VkDescriptorSetLayoutBinding> layoutBindings;
  std::vector<VkDescriptorPoolSize> sizes;
  for (const CheckBinding& b : bindings) {
    layoutBindings.push_back({b.binding, b.type, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr});
    sizes.push_back({b.type, 1});
  }
  DescriptorSetLayout setLayout = createLayout(ctx, layoutBindings, name + " set layout");
  DescriptorPool pool = createPool(ctx, sizes, 1, name + " pool");
  VkDescriptorSet set = allocateDescriptorSet(ctx, pool.get(), setLayout.get(), name + " set");
  for (const CheckBinding& b : bindings) {
    if (b.type == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER)
      writeUniformBuffer(ctx, set, b.buffer, b.range, b.binding);
    else
      writeStorageBuffer(ctx, set, b.buffer, b.binding);
  }
  const VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, static_cast<uint32_t>(push.size())};
  const VkDescriptorSetLayout layouts[] = {setLayout.get()};
  PipelineLayout layout =
      createPipelineLayout(ctx, layouts, push.empty() ? std::span<const VkPushConstantRange>{} : std::span(&range, 1),
                           name + " pipeline layout");
  Pipeline pipeline = createComputePipeline(ctx, layout.get(), spirv, name + " pipeline");
  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.get());
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout.get(), 0, 1, &set, 0, nullptr);
    if (!push.empty())
      vkCmdPushConstants(cmd, layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, static_cast<uint32_t>(push.size()),
                         push.data());
    vkCmdDispatch(cmd, (threads + 63) / 64, 1, 1);
    hostReadBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  });
}

}  // namespace vegstream::render::testing
