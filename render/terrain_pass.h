#pragma once
// The terrain surface: one indexed draw of the current TerrainMesh, drawn camera-relative and
// coloured by the imagery texture where there is one (by height and slope elsewhere).

#include <functional>

#include "render/frame_types.h"
#include "render/gpu_resources.h"
#include "render/handle.h"
#include "terrain/terrain_mesh.h"

namespace vegstream::render {

class TerrainPass {
 public:
  TerrainPass(const Context& ctx, VkDescriptorSetLayout frameLayout, VkSampleCountFlagBits samples);

  using Retire = std::function<void(GpuBuffer&&, GpuImage&&)>;

  // Uploads a new mesh and imagery (null: none). The previous GPU objects go to `retire`,
  // which must keep them alive until the frames that use them have finished on the GPU.
  void setMesh(const terrain::TerrainMesh& mesh, const ColorImage* imagery, const Retire& retire);

  // Records the draw; returns the number of triangles submitted.
  uint64_t record(VkCommandBuffer cmd, VkDescriptorSet frameSet, const glm::dvec3& cameraPosition) const;

  uint64_t gpuBytes() const { return gpuBytes_; }

 private:
  void uploadImagery(const ColorImage& image);
  void writeImageryDescriptor();

  const Context* ctx_;
  DescriptorSetLayout imageryLayout_;
  DescriptorPool imageryPool_;
  VkDescriptorSet imagerySet_ = VK_NULL_HANDLE;
  Sampler sampler_;
  PipelineLayout layout_;
  Pipeline pipeline_;
  GpuBuffer vertices_, indices_;
  GpuImage imagery_;
  bool hasImagery_ = false;
  uint32_t indexCount_ = 0;
  uint64_t gpuBytes_ = 0;
  glm::dvec3 origin_{0.0};
};

}  // namespace vegstream::render
