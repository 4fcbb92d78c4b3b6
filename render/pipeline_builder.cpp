#include "render/pipeline_builder.h"

#include "render/create_named.h"

namespace vegstream::render {

ShaderModule createShaderModule(const Context& ctx, std::span<const uint32_t> spirv, const std::string& name) {
  VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  ci.codeSize = spirv.size_bytes();
  ci.pCode = spirv.data();
  return createNamed<ShaderModule>(ctx, VK_OBJECT_TYPE_SHADER_MODULE, name, "vkCreateShaderModule",
                                   vkCreateShaderModule, ci);
}

Pipeline createComputePipeline(const Context& ctx, VkPipelineLayout layout, std::span<const uint32_t> spirv,
                               const std::string& name) {
  ShaderModule module = createShaderModule(ctx, spirv, name + " shader");
  VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  ci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  ci.stage.module = module.get();
  ci.stage.pName = "main";
  ci.layout = layout;
  return createNamed<Pipeline>(ctx, VK_OBJECT_TYPE_PIPELINE, name, "vkCreateComputePipelines", [&](VkPipeline* raw) {
    return vkCreateComputePipelines(ctx.device(), VK_NULL_HANDLE, 1, &ci, nullptr, raw);
  });
}

PipelineLayout createPipelineLayout(const Context& ctx, std::span<const VkDescriptorSetLayout> sets,
                                    std::span<const VkPushConstantRange> pushConstants, const std::string& name) {
  VkPipelineLayoutCreateInfo ci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  ci.setLayoutCount = static_cast<uint32_t>(sets.size());
  ci.pSetLayouts = sets.data();
  ci.pushConstantRangeCount = static_cast<uint32_t>(pushConstants.size());
  ci.pPushConstantRanges = pushConstants.data();
  return createNamed<PipelineLayout>(ctx, VK_OBJECT_TYPE_PIPELINE_LAYOUT, name, "vkCreatePipelineLayout",
                                     vkCreatePipelineLayout, ci);
}

namespace {

// The desc's vertex bindings and attributes (pointing into desc).
VkPipelineVertexInputStateCreateInfo vertexInput(const GraphicsPipelineDesc& desc) {
  VkPipelineVertexInputStateCreateInfo vi{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  vi.vertexBindingDescriptionCount = static_cast<uint32_t>(desc.bindings.size());
  vi.pVertexBindingDescriptions = desc.bindings.data();
  vi.vertexAttributeDescriptionCount = static_cast<uint32_t>(desc.attributes.size());
  vi.pVertexAttributeDescriptions = desc.attributes.data();
  return vi;
}

// Filled polygons, the desc's culling, front faces counter-clockwise, its depth bias (dynamic).
VkPipelineRasterizationStateCreateInfo rasterizationState(const GraphicsPipelineDesc& desc) {
  VkPipelineRasterizationStateCreateInfo rs{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  rs.polygonMode = VK_POLYGON_MODE_FILL;
  rs.cullMode = desc.cullMode;
  // The projection flips y for Vulkan's y-down framebuffer, so a triangle that is
  // counter-clockwise seen from its front stays counter-clockwise in Vulkan's terms.
  rs.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  rs.lineWidth = 1.0f;
  if (desc.depthBias) rs.depthBiasEnable = VK_TRUE;
  return rs;
}

VkPipelineDepthStencilStateCreateInfo depthState(const GraphicsPipelineDesc& desc) {
  VkPipelineDepthStencilStateCreateInfo ds{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  ds.depthTestEnable = desc.depthTest ? VK_TRUE : VK_FALSE;
  ds.depthWriteEnable = desc.depthWrite ? VK_TRUE : VK_FALSE;
  ds.depthCompareOp = desc.depthCompare;
  return ds;
}

// Every channel written; with alphaBlend, over what is there.
VkPipelineColorBlendAttachmentState blendAttachment(const GraphicsPipelineDesc& desc) {
  VkPipelineColorBlendAttachmentState blend{};
  blend.colorWriteMask =
      VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
  if (desc.alphaBlend) {
    blend.blendEnable = VK_TRUE;
    blend.srcColorBlendFactor = VK_BLEND_FACTOR_SRC_ALPHA;
    blend.dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
    blend.colorBlendOp = VK_BLEND_OP_ADD;
    blend.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
    blend.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
    blend.alphaBlendOp = VK_BLEND_OP_ADD;
  }
  return blend;
}

}  // namespace

Pipeline createGraphicsPipeline(const Context& ctx, const GraphicsPipelineDesc& desc) {
  std::vector<ShaderModule> modules;
  std::vector<VkPipelineShaderStageCreateInfo> stages;
  for (const auto& s : desc.stages) {
    modules.push_back(createShaderModule(ctx, s.spirv, desc.name + " shader"));
    VkPipelineShaderStageCreateInfo si{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    si.stage = s.stage;
    si.module = modules.back().get();
    si.pName = "main";
    stages.push_back(si);
  }
  const VkPipelineVertexInputStateCreateInfo vi = vertexInput(desc);
  VkPipelineInputAssemblyStateCreateInfo ia{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  ia.topology = desc.topology;
  VkPipelineViewportStateCreateInfo vp{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  vp.viewportCount = 1;
  vp.scissorCount = 1;
  const VkPipelineRasterizationStateCreateInfo rs = rasterizationState(desc);
  VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  ms.rasterizationSamples = desc.samples;
  VkPipelineTessellationStateCreateInfo ts{VK_STRUCTURE_TYPE_PIPELINE_TESSELLATION_STATE_CREATE_INFO};
  ts.patchControlPoints = desc.patchControlPoints;
  const VkPipelineDepthStencilStateCreateInfo ds = depthState(desc);
  const VkPipelineColorBlendAttachmentState blend = blendAttachment(desc);
  const uint32_t attachments = desc.colorFormat == VK_FORMAT_UNDEFINED ? 0u : desc.colorAttachments;
  const std::vector<VkPipelineColorBlendAttachmentState> blends(attachments, blend);
  const std::vector<VkFormat> formats(attachments, desc.colorFormat);
  VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  cb.attachmentCount = attachments;
  cb.pAttachments = blends.data();
  const VkDynamicState dynamicStates[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR,
                                          VK_DYNAMIC_STATE_DEPTH_BIAS};
  VkPipelineDynamicStateCreateInfo dyn{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dyn.dynamicStateCount = desc.depthBias ? 3u : 2u;
  dyn.pDynamicStates = dynamicStates;
  VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
  rendering.colorAttachmentCount = attachments;
  rendering.pColorAttachmentFormats = formats.data();
  rendering.depthAttachmentFormat = desc.depthFormat;

  VkGraphicsPipelineCreateInfo ci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, &rendering};
  ci.stageCount = static_cast<uint32_t>(stages.size());
  ci.pStages = stages.data();
  ci.pVertexInputState = &vi;
  ci.pInputAssemblyState = &ia;
  ci.pViewportState = &vp;
  ci.pRasterizationState = &rs;
  ci.pMultisampleState = &ms;
  ci.pTessellationState = desc.patchControlPoints > 0 ? &ts : nullptr;
  ci.pDepthStencilState = &ds;
  ci.pColorBlendState = &cb;
  ci.pDynamicState = &dyn;
  ci.layout = desc.layout;
  const std::string what = "vkCreateGraphicsPipelines(" + desc.name + ")";
  return createNamed<Pipeline>(ctx, VK_OBJECT_TYPE_PIPELINE, desc.name, what.c_str(), [&](VkPipeline* pipeline) {
    return vkCreateGraphicsPipelines(ctx.device(), VK_NULL_HANDLE, 1, &ci, nullptr, pipeline);
  });
}

}  // namespace vegstream::render
