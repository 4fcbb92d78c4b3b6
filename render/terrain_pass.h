#pragma once
// The terrain surface: each frame, the TerrainDraws of the FrameRequest (meshes of terrain
// pieces, drawn camera-relative, one draw each) coloured from the imagery texture array (one
// 256 × 256 tile per layer), with imagery fade-in driven by push constants (geomorphing is the
// CPU's: the meshes arrive at their drawn heights).
//
// Two ways to shade it, the same colours (terrain_shading.glsl serves both):
// - forward: the terrain pipeline shades every fragment it rasterises;
// - deferred: the visibility pipeline writes only which triangle each sample sees, and
//   TerrainShadePass shades every pixel in compute. On GPUs whose graphics units are few next
//   to their compute units (NVIDIA's H100/H200 run fragment work on two of their 66 TPCs) this
//   takes the shading off the scarce units; see render/README.md for the measurements.
// Either way the pieces are drawn front to back (nearest bounding-box point first), so early
// depth testing rejects most hidden fragments before they cost shading or ROP writes.
//
// Geometry lives in TerrainGeometryBuffers (render/terrain_geometry_buffers.h): each frame's
// index buffer holds every piece's triangles in draw order, and the vertices stay resident on
// the GPU, ROAM's chunks uploaded only when new or moved (or, with RendererOptions::
// residentTerrain false, flattened and copied every frame). The pieces are drawn through an
// indirect list, one indexed command per piece whose first instance is the piece's index into
// the slot's pieces (set 3; shaders/common/terrain_draw.glsl), in one call where the device has
// multiDrawIndirect and drawIndirectFirstInstance (else one direct draw per piece, the same
// commands). Imagery arrives through a
// per-frame-slot staging buffer (a ring of kSlots) and lands in its layer before the draws.
//
// Close up, the imagery gets detail textures blended by the colour score of its colour (core
// seed 001 §3.3; render/detail_textures.h owns them and the terrain-type table, bound as set 2),
// fading out with distance.

#include <array>
#include <functional>
#include <span>
#include <vector>

#include <glm/vec4.hpp>

#include "core/task_runner.h"
#include "render/detail_textures.h"
#include "render/frame_slots.h"
#include "render/frame_types.h"
#include "render/gpu_resources.h"
#include "render/growing_buffer.h"
#include "render/handle.h"
#include "render/terrain_geometry_buffers.h"
#include "terrain/terrain_mesh.h"

namespace vegstream::render {

// One drawn piece (std430; Piece in shaders/common/terrain_piece.glsl), read by the draws
// (the piece at gl_InstanceIndex), the deferred shade and the compute raster.
struct TerrainPiece {
  glm::vec4 originFromCamera;
  glm::vec4 imageryUv;
  glm::vec4 previousUv;
  glm::vec4 layers;
  glm::uvec4 range;  // x: first triangle, y: vertex offset, z: triangles
};
static_assert(sizeof(TerrainPiece) == 80);

// The geometry a prepared frame slot holds, for the shade pass.
struct TerrainGeometry {
  VkBuffer vertices = VK_NULL_HANDLE;
  VkBuffer indices = VK_NULL_HANDLE;
  VkBuffer pieces = VK_NULL_HANDLE;
  uint32_t pieceCount = 0;
};

class TerrainPass {
 public:
  static constexpr int kSlots = kFramesInFlight;  // frames in flight

  // `deferred`: also build the visibility pipeline (the device can shade in compute). `tasks`
  // (may be null: all on the calling thread) shares prepare()'s per-piece work with the calling
  // thread; it must outlive the pass; it also makes the slots' buffers' next sizes ahead of need
  // (growing_buffer.h). `reserveTriangles`: the geometry buffers' smallest size, in
  // triangles (RendererOptions::terrainTriangles). `residentGeometry`: the vertices kept on the
  // GPU (terrain_geometry_buffers.h), or copied every frame.
  TerrainPass(const Context& ctx, VkDescriptorSetLayout frameLayout, VkSampleCountFlagBits samples, bool deferred,
              TaskRunner* tasks = nullptr, uint64_t reserveTriangles = 0, bool residentGeometry = true);

  using RetireImage = std::function<void(GpuImage&&)>;
  using RetireBuffer = std::function<void(GpuBuffer&&)>;

  // A new imagery array of `layers` layers (≥ 1; contents undefined until uploaded). The old one
  // goes to `retire`, which keeps it alive until the frames that use it have finished.
  // With companions, a parallel RG8 array holds each layer's NDVI (R, ImageryUpload::ndvi) and
  // landcover classes (G, ::landcover) for the classify pass and the terrain's detail; without,
  // a one-layer placeholder keeps its descriptor valid.
  void setImageryLayers(uint32_t layers, ImageryCompanions companions, const RetireImage& retire);
  uint32_t imageryLayers() const { return layers_; }
  ImageryCompanions companions() const { return companions_; }
  // The companion array (RG8 UNORM: the NDVI byte of datasets/tile_codec.h, the class code of
  // datasets/landcover.h as code / 255), shader-readable like the imagery.
  VkImageView companionView() const { return companionArray_.view.get(); }
  // The imagery array seen as UNORM (the sRGB bytes undecoded; shader-readable after
  // recordUploads), for the classify pass, which decodes them exactly as the CPU does.
  VkImageView imageryBytesView() const { return imagery_.alternateView.get(); }
  // The imagery array as sRGB (sampled as linear colour), for the plant pipelines.
  VkImageView imageryView() const { return imagery_.view.get(); }
  // Sets 1 (imagery) and 2 (detail) of the terrain pipelines, for the shade pass.
  VkDescriptorSetLayout imageryLayout() const { return imageryLayout_.get(); }
  VkDescriptorSet imagerySet() const { return imagerySet_; }
  const DetailTextures& detail() const { return detail_; }
  // The terrain types of a new species catalog (vegetation/terrain_types.h); the GPU must be idle.
  void setTerrainTypes(std::span<const vegetation::TerrainType> types) { detail_.setTypes(types); }

  // Records the uploads (outside rendering) into `cmd` for frame slot `slot`.
  void recordUploads(VkCommandBuffer cmd, int slot, std::span<const ImageryUpload> uploads, const RetireBuffer& retire);

  // Outside rendering: orders the draws front to back, copies their geometry into slot `slot`'s
  // buffers (recording the copy to device-local memory) and keeps the draw list for
  // recordForward / recordVisibility; returns the triangles to draw. The pieces' bounds and
  // copies run in parallel on the pass's TaskRunner and the calling thread (each piece has its
  // own range of the buffers, so the bytes are the same whatever ran where).
  uint64_t prepare(VkCommandBuffer cmd, int slot, const glm::dvec3& cameraPosition, std::span<const TerrainDraw> draws,
                   const RetireBuffer& retire);
  // Inside rendering into the colour + depth targets: the prepared draws, shaded.
  void recordForward(VkCommandBuffer cmd, int slot, VkDescriptorSet frameSet) const;
  // Inside rendering into the visibility + depth targets: the prepared draws' triangle ids.
  void recordVisibility(VkCommandBuffer cmd, int slot, VkDescriptorSet frameSet) const;
  TerrainGeometry geometry(int slot) const;
  // The last prepare()'s chunks drawn and uploaded, vertices uploaded (zero when copied).
  const ChunkCacheFigures& geometryFigures() const { return geometry_.figures(); }

  // Imagery array + detail textures + geometry buffers of every slot.
  uint64_t gpuBytes() const;

 private:
  void recordDraws(VkCommandBuffer cmd, int slot, VkDescriptorSet frameSet, VkPipeline pipeline) const;
  // The constructor's pipelines: the forward one, and the visibility one when deferred.
  void createPipelines(VkDescriptorSetLayout frameLayout, VkSampleCountFlagBits samples, bool deferred);

  const Context* ctx_;
  TaskRunner* tasks_;
  DetailTextures detail_;
  DescriptorSetLayout imageryLayout_;
  DescriptorPool imageryPool_;
  VkDescriptorSet imagerySet_ = VK_NULL_HANDLE;
  Sampler sampler_;
  PipelineLayout layout_;
  Pipeline pipeline_;            // forward shading
  Pipeline visibilityPipeline_;  // deferred: triangle ids only (null when not deferred)
  GpuImage imagery_;
  GpuImage companionArray_;  // RG8: NDVI, landcover class
  ImageryCompanions companions_;
  uint32_t layers_ = 0;
  std::array<GrowingBuffer, kSlots> pieces_, staging_;  // host-visible
  // The draw list: one indexed indirect command per piece, its first instance the piece's index.
  std::array<GrowingBuffer, kSlots> drawList_;
  std::array<uint32_t, kSlots> drawCount_{};
  std::array<std::vector<VkDrawIndexedIndirectCommand>, kSlots> draws_;  // without multi-draw: drawn one by one
  bool multiDraw_ = false;
  DescriptorSetLayout piecesLayout_;  // set 3 of the draws: the slot's pieces
  DescriptorPool piecesPool_;
  std::array<VkDescriptorSet, kSlots> piecesSets_{};
  TerrainGeometryBuffers geometry_;
};

// The draw order of `draws`: front to back by the distance from `cameraPosition` to each
// mesh's bounding box (ties keep their order, so the order is deterministic); draws without
// triangles are left out. A chunk's box is its own (terrain::TerrainChunk::boundsMin / boundsMax).
// The bounds are found on `tasks` (and the calling thread) when given.
std::vector<uint32_t> frontToBackOrder(std::span<const TerrainDraw> draws, const glm::dvec3& cameraPosition,
                                       TaskRunner* tasks = nullptr);

}  // namespace vegstream::render
