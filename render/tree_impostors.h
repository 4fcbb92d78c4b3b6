#pragma once
// Octahedral impostors of the tree models (issue 20), rendered once at start-up from the models
// themselves: per model one layer of two RGBA8 atlases of G × G cells — albedo with coverage, and
// the model-space normal with depth — cell (i, j) seen orthographically from the hemisphere
// direction of shaders/common/tree_impostor.glsl (treeImpostorDirection), over a square of half
// extent `halfExtent` around the model's centre. kImpostorSamples samples per texel (resolved by
// averaging when more than one, so alpha is the share covered): one on every device — 4 samples
// matched the model's coverage no better in tests/render/tree_render_test.cpp (1.0 / 3.5 % against
// 1.3 / 3.8 %) and tripled the capture on lavapipe (4.9 s against 1.6 s for six models, at 64 px cells). The
// background is empty (0), so bilinear lookups come premultiplied by coverage and the shader
// divides by it. Lit at run time (shaders/tree_impostor.frag).

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/result.h"
#include "render/context.h"
#include "render/gpu_resources.h"
#include "render/handle.h"

namespace vegstream::render {

inline constexpr uint32_t kImpostorViews = 8;    // G: cells per side
inline constexpr uint32_t kImpostorCellPx = 96;  // pixels per cell side (sharp enough at the 5-height switch)
// Mip levels of the atlases (96, 48, 24, 12 pixels a cell): each level a 2 × 2 box of the one
// above, never across a cell's edge (every level's cell side is even), so an impostor seen from
// afar reads its texels' average coverage — a crown's share covered, whorl gaps included — rather
// than a point of it (issue 41 items 5 and 6: a forest seen from above closes as its crowns do).
inline constexpr uint32_t kImpostorMipLevels = 4;
inline constexpr VkSampleCountFlagBits kImpostorSamples = VK_SAMPLE_COUNT_1_BIT;  // see above

// The C++ twin of common/tree_impostor.glsl.
glm::vec3 impostorDirection(glm::vec2 uv);
void impostorBasis(glm::vec3 towardsViewer, glm::vec3& right, glm::vec3& up);

struct TreeImpostorModel {
  float centreZ = 0.0f;     // the model's centre height
  float halfExtent = 0.0f;  // the half side of the square every cell covers
};

class TreeImpostors {
 public:
  // Draws model `m` into every cell of the bound two-attachment target, one instance per cell
  // (the caller's tree pipeline in capture mode: shaders/tree.vert places each instance; one draw
  // per model, where lavapipe spent most of 5 s on 64 small draws per model).
  using DrawModel = std::function<void(VkCommandBuffer, uint32_t model)>;
  TreeImpostors(const Context& ctx, std::span<const TreeImpostorModel> models, const DrawModel& draw);
  // The atlases of `layers` models from their pixels (pixelBytes(layers), in readPixels' order),
  // which `fill` writes straight into the upload's staging memory; an error from `fill` is
  // returned (no atlas). For the impostors kept between processes (impostor_atlas_file.h).
  using FillPixels = std::function<Status(std::span<uint8_t>)>;
  static Result<std::unique_ptr<TreeImpostors>> fromPixels(const Context& ctx, uint32_t layers, const FillPixels& fill);

  const GpuImage& albedo() const { return albedo_; }
  const GpuImage& normalDepth() const { return normal_; }
  uint64_t gpuBytes() const {
    return albedo_.bytes + normal_.bytes;
  }
  // Every level of both atlases, for every layer: the albedo's levels 0 … kImpostorMipLevels − 1,
  // then the normal + depth's, each level its layers one after another, rows top down, RGBA8.
  static uint64_t pixelBytes(uint32_t layers);
  uint32_t layers() const { return albedo_.layers; }
  // Reads all of them back (in that order) and hands them to `use`. Waits for the GPU.
  void readPixels(const std::function<void(std::span<const uint8_t>)>& use) const;
  // Reads one layer's albedo atlas back at mip `level` (RGBA8, row-major): for tests. Waits for the GPU.
  std::vector<uint8_t> readAlbedo(uint32_t layer, uint32_t level = 0) const;

 private:
  // Renders model `layer` from every direction into its layer of the atlas (views keeps the
  // layer's attachment views alive until the capture has run).
  void captureLayer(VkCommandBuffer cmd, uint32_t layer, std::vector<ImageView>& views, const DrawModel& draw);
  // After the capture (level 0 in the colour-attachment layout): levels 1 … kImpostorMipLevels − 1
  // of both atlases, each blitted from the one above; every level left shader-readable.
  void buildMips(VkCommandBuffer cmd, uint32_t layers) const;
  explicit TreeImpostors(const Context& ctx) : ctx_(&ctx) {}
  // One copy region per atlas and level, at its offset in pixelBytes' order.
  std::vector<std::pair<const GpuImage*, VkBufferImageCopy>> pixelRegions() const;

  const Context* ctx_;
  GpuImage albedo_, normal_;
  GpuImage depth_, msAlbedo_, msNormal_;  // the capture's targets, released after it
};

}  // namespace vegstream::render
