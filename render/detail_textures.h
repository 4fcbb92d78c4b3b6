#pragma once
// The terrain pass's detail set (set 2 of its pipeline layout): binding 0 the detail texture
// array (one layer per vegetation::DetailSurface, RGBA8 UNORM modulation, full mip chain,
// trilinear + repeat), binding 1 the TerrainDetail uniform block (render/terrain_detail.h: the
// terrain-type table and the tiling / fade settings). Both are made once, at renderer start:
// the patterns are generated on the CPU (render/detail_patterns.h) and uploaded through a
// staging buffer; nothing changes per frame, so one set serves every frame slot.

#include <span>

#include "render/context.h"
#include "render/gpu_resources.h"
#include "render/handle.h"
#include "render/terrain_detail.h"
#include "vegetation/terrain_types.h"

namespace vegstream::render {

class DetailTextures {
 public:
  DetailTextures(const Context& ctx, std::span<const vegetation::TerrainType> types,
                 const DetailSettings& settings = {});

  // A new type table (the species catalog changed). The GPU must be idle: the block is replaced.
  void setTypes(std::span<const vegetation::TerrainType> types);

  VkDescriptorSetLayout layout() const { return layout_.get(); }
  VkDescriptorSet set() const { return set_; }
  // Texture array + uniform block.
  uint64_t gpuBytes() const { return image_.bytes + uniforms_.size; }

 private:
  DescriptorSetLayout layout_;
  DescriptorPool pool_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  Sampler sampler_;
  GpuImage image_;
  GpuBuffer uniforms_;
  const Context* ctx_ = nullptr;
  DetailSettings settings_;
};

}  // namespace vegstream::render
