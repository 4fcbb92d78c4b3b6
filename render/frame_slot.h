#pragma once
// Private to render/: what one frame in flight owns (its command buffer, fence, uniforms, timer,
// read-back buffers and descriptor sets, and what was submitted in it), set 0 of every pass (the
// frame set's layout and pool), and the slot's read-back images. The slots are the frame
// submitter's (frame_submitter.h); the passes record into them (frame_passes.h).

#include <cstdint>
#include <memory>
#include <optional>

#include <glm/mat4x4.hpp>

#include "render/context.h"
#include "render/frame_types.h"
#include "render/gpu_resources.h"
#include "render/gpu_timer.h"
#include "render/handle.h"
#include "render/renderer.h"
#include "render/terrain_chunk_cache.h"
#include "render/shadow_cascades.h"

namespace vegstream::render {

inline constexpr int kMaxPasses = 16;  // the GPU timer's passes a frame

// Everything one frame in flight owns.
struct FrameSlot {
  CommandPool pool;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  Fence fence;
  Semaphore imageAcquired;
  GpuBuffer uniforms;
  VkDescriptorSet descriptorSet = VK_NULL_HANDLE;
  VkDescriptorSet shadowPassSet = VK_NULL_HANDLE;  // the same, but binding 4 a placeholder: the shadow pass's own
  std::unique_ptr<GpuTimer> timer;
  GpuBuffer colorReadback, depthReadback;
  GpuBuffer aovReadback;  // an AOV frame's resolved float target; made by the slot's first AOV frame
  // What was submitted last in this slot.
  uint64_t frameIndex = 0;
  bool submitted = false;
  bool readColor = false, readDepth = false;
  bool readAov = false;                  // an AOV frame: aovReadback holds the resolved float target
  glm::dmat4 aovInverseProjection{1.0};  // its camera's, for the distances
  double cpuRecordMs = 0.0;
  uint64_t terrainTriangles = 0;
  ChunkCacheFigures terrainGeometry;  // the terrain's chunks drawn and uploaded (TerrainPass::prepare)
  std::optional<VegetationFigures> vegetation;
  bool bladesExpanded = false;            // the compute blade path drew this frame's plants
  bool treesDrawn = false;                // the tree pass classified this frame's trees
  bool hizEarly = false;                  // the Hi-Z pyramid is built right after the terrain (before the trees)
  std::optional<ShadowCascades> shadows;  // the sun's shadow map holds this frame's trees
};

// Set 0 of every pass: the frame's uniforms, and the shared simulation's block, wind cells and
// interaction field (render/simulation_pass.h), which every plant stage may read.
DescriptorSetLayout createFrameSetLayout(const Context& ctx);
// The pool of every slot's two frame sets (the second is the shadow pass's).
DescriptorPool createFrameSetPool(const Context& ctx);

// Slot `index`'s command pool and buffer, fence, semaphore, uniforms, timer and colour and depth
// read-back buffers for `pixels` pixels; its descriptor sets are the renderer's to write.
void createFrameSlot(const Context& ctx, FrameSlot& s, int index, VkDeviceSize pixels);

// The colour, depth and AOV images the slot's frame read back (as it asked), into r.
void readSlotImages(const FrameSlot& slot, VkExtent2D extent, FrameResult& r);

}  // namespace vegstream::render
