#pragma once
// Graphics pipelines for dynamic rendering into RenderTargets: one description struct, one
// function, so every pass states only what differs (shaders, vertex layout, depth, blending).

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "render/context.h"
#include "render/handle.h"

namespace vegstream::render {

ShaderModule createShaderModule(const Context& ctx, std::span<const uint32_t> spirv, const std::string& name);

struct ShaderStage {
  VkShaderStageFlagBits stage;
  std::span<const uint32_t> spirv;
};

struct GraphicsPipelineDesc {
  std::string name;
  std::vector<ShaderStage> stages;
  std::vector<VkVertexInputBindingDescription> bindings;
  std::vector<VkVertexInputAttributeDescription> attributes;
  VkPrimitiveTopology topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkCullModeFlags cullMode = VK_CULL_MODE_BACK_BIT;
  bool depthTest = true;
  bool depthWrite = true;
  VkCompareOp depthCompare = VK_COMPARE_OP_GREATER;  // reverse-Z
  VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
  bool alphaBlend = false;          // straight alpha over the target (overlays); off: opaque writes
  uint32_t patchControlPoints = 0;  // > 0: tessellation (topology PATCH_LIST)
  VkFormat colorFormat = VK_FORMAT_UNDEFINED;
  uint32_t colorAttachments = 1;  // > 1: that many attachments, all of colorFormat (impostor capture)
  bool depthBias = false;         // a slope-scaled depth bias, set per draw (shadow maps)
  VkFormat depthFormat = VK_FORMAT_UNDEFINED;
  VkPipelineLayout layout = VK_NULL_HANDLE;
};

Pipeline createGraphicsPipeline(const Context& ctx, const GraphicsPipelineDesc& desc);

// A compute pipeline of one shader (entry point "main"), named `name`.
Pipeline createComputePipeline(const Context& ctx, VkPipelineLayout layout, std::span<const uint32_t> spirv,
                               const std::string& name);

PipelineLayout createPipelineLayout(const Context& ctx, std::span<const VkDescriptorSetLayout> sets,
                                    std::span<const VkPushConstantRange> pushConstants, const std::string& name);

}  // namespace vegstream::render
