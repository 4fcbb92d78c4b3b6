#pragma once
// The terrain surface: one indexed draw of the current TerrainMesh, drawn camera-relative.

#include <functional>

#include "render/gpu_resources.h"
#include "render/handle.h"
#include "terrain/terrain_mesh.h"

namespace vegstream::render {

class TerrainPass {
 public:
  TerrainPass(const Context& ctx, VkDescriptorSetLayout frameLayout, VkSampleCountFlagBits samples);

  // Uploads a new mesh. The previous buffers go to `retire`, which must keep them alive until
  // the frames that use them have finished on the GPU.
  void setMesh(const terrain::TerrainMesh& mesh, const std::function<void(GpuBuffer&&)>& retire);

  // Records the draw; returns the number of triangles submitted.
  uint64_t record(VkCommandBuffer cmd, VkDescriptorSet frameSet, const glm::dvec3& cameraPosition) const;

 private:
  const Context* ctx_;
  PipelineLayout layout_;
  Pipeline pipeline_;
  GpuBuffer vertices_, indices_;
  uint32_t indexCount_ = 0;
  glm::dvec3 origin_{0.0};
};

}  // namespace vegstream::render
