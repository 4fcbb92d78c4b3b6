#pragma once
// The terrain surface: each frame, the TerrainDraws of the FrameRequest (meshes of terrain
// pieces, drawn camera-relative, one draw each) coloured from the imagery texture array (one
// 256 × 256 tile per layer), with imagery fade-in driven by push constants (geomorphing is the
// CPU's: the meshes arrive at their drawn heights).
//
// Geometry is copied each frame into the frame slot's host-visible vertex/index buffers: the
// terrain changes as tiles stream in and as ROAM refines, and copying a few MB is cheaper than
// managing thousands of small buffers. A mesh's chunks (terrain_mesh.h) are flattened into its
// piece's range (one draw per piece); their ids and versions would let a GPU-resident cache
// upload only the changed ones, which is not done yet. Imagery arrives through a per-frame-slot staging
// buffer (a ring of kSlots) and lands in its layer before the draws.
//
// Close up, the imagery gets detail textures blended by the colour score of its colour (core
// seed 001 §3.3; render/detail_textures.h owns them and the terrain-type table, bound as set 2),
// fading out with distance.

#include <array>
#include <functional>
#include <span>

#include "render/detail_textures.h"
#include "render/frame_types.h"
#include "render/gpu_resources.h"
#include "render/handle.h"
#include "terrain/terrain_mesh.h"

namespace vegstream::render {

class TerrainPass {
 public:
  static constexpr int kSlots = 2;  // frames in flight

  TerrainPass(const Context& ctx, VkDescriptorSetLayout frameLayout, VkSampleCountFlagBits samples);

  using RetireImage = std::function<void(GpuImage&&)>;
  using RetireBuffer = std::function<void(GpuBuffer&&)>;

  // A new imagery array of `layers` layers (≥ 1; contents undefined until uploaded). The old one
  // goes to `retire`, which keeps it alive until the frames that use it have finished.
  void setImageryLayers(uint32_t layers, const RetireImage& retire);
  uint32_t imageryLayers() const { return layers_; }
  // The imagery array seen as UNORM (the sRGB bytes undecoded; shader-readable after
  // recordUploads), for the classify pass, which decodes them exactly as the CPU does.
  VkImageView imageryBytesView() const { return imagery_.alternateView.get(); }
  // The imagery array as sRGB (sampled as linear colour), for the plant pipelines.
  VkImageView imageryView() const { return imagery_.view.get(); }

  // Records the uploads (outside rendering) into `cmd` for frame slot `slot`.
  void recordUploads(VkCommandBuffer cmd, int slot, std::span<const ImageryUpload> uploads, const RetireBuffer& retire);

  // Copies the draws' geometry into slot `slot`'s buffers and records the draws (inside
  // rendering); returns the triangles submitted.
  uint64_t record(VkCommandBuffer cmd, int slot, VkDescriptorSet frameSet, const glm::dvec3& cameraPosition,
                  std::span<const TerrainDraw> draws, const RetireBuffer& retire);

  // Imagery array + detail textures + geometry buffers of both slots.
  uint64_t gpuBytes() const;

 private:
  void ensureCapacity(GpuBuffer& buffer, VkDeviceSize bytes, VkBufferUsageFlags usage, const char* what, int slot,
                      const RetireBuffer& retire);

  const Context* ctx_;
  DetailTextures detail_;
  DescriptorSetLayout imageryLayout_;
  DescriptorPool imageryPool_;
  VkDescriptorSet imagerySet_ = VK_NULL_HANDLE;
  Sampler sampler_;
  PipelineLayout layout_;
  Pipeline pipeline_;
  GpuImage imagery_;
  uint32_t layers_ = 0;
  std::array<GpuBuffer, kSlots> vertices_, indices_, staging_;
};

}  // namespace vegstream::render
