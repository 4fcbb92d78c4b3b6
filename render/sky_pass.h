#pragma once
// The sky: a full-screen triangle at the far plane, coloured by shaders/common/atmosphere.glsl.

#include "render/context.h"
#include "render/handle.h"

namespace vegstream::render {

class SkyPass {
 public:
  SkyPass(const Context& ctx, VkDescriptorSetLayout frameLayout, VkSampleCountFlagBits samples);
  void record(VkCommandBuffer cmd, VkDescriptorSet frameSet) const;

 private:
  PipelineLayout layout_;
  Pipeline pipeline_;
};

}  // namespace vegstream::render
