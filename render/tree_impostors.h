#pragma once
// Octahedral impostors of the tree models (issue 20), rendered once at start-up from the models
// themselves: per model one layer of two RGBA8 atlases of G × G cells — albedo with coverage, and
// the model-space normal with depth — cell (i, j) seen orthographically from the hemisphere
// direction of shaders/common/tree_impostor.glsl (treeImpostorDirection), over a square of half
// extent `halfExtent` around the model's centre. Captured with kImpostorSamples samples per texel
// and resolved by averaging, so a texel's alpha is the share of it the model covers (and its
// colour and normal are premultiplied by it): the impostor then covers, on average, what the
// model covers at any size. Lit at run time (shaders/tree_impostor.frag).

#include <cstdint>
#include <functional>
#include <span>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "render/context.h"
#include "render/gpu_resources.h"

namespace vegstream::render {

inline constexpr uint32_t kImpostorViews = 8;    // G: cells per side
inline constexpr uint32_t kImpostorCellPx = 64;  // pixels per cell side
inline constexpr VkSampleCountFlagBits kImpostorSamples = VK_SAMPLE_COUNT_4_BIT;

// The C++ twin of common/tree_impostor.glsl.
glm::vec3 impostorDirection(glm::vec2 uv);
void impostorBasis(glm::vec3 towardsViewer, glm::vec3& right, glm::vec3& up);
// The capture camera of cell (i, j) for a model whose centre is at height `centreZ` (model space,
// metres) and whose bounding radius is `halfExtent`: orthographic, reverse-Z (nearest 1).
glm::mat4 impostorCaptureMatrix(uint32_t i, uint32_t j, float centreZ, float halfExtent);

struct TreeImpostorModel {
  float centreZ = 0.0f;     // the model's centre height
  float halfExtent = 0.0f;  // the half side of the square every cell covers
};

class TreeImpostors {
 public:
  // Draws model `m` with the capture matrix into the bound two-attachment target (the caller's
  // tree pipeline in capture mode).
  using DrawModel = std::function<void(VkCommandBuffer, uint32_t model, const glm::mat4& capture)>;
  TreeImpostors(const Context& ctx, std::span<const TreeImpostorModel> models, const DrawModel& draw);

  const GpuImage& albedo() const { return albedo_; }
  const GpuImage& normalDepth() const { return normal_; }
  uint64_t gpuBytes() const {
    return albedo_.bytes + normal_.bytes + depth_.bytes + msAlbedo_.bytes + msNormal_.bytes;
  }
  // Reads one layer's albedo atlas back (RGBA8, row-major): for tests. Waits for the GPU.
  std::vector<uint8_t> readAlbedo(uint32_t layer) const;

 private:
  const Context* ctx_;
  GpuImage albedo_, normal_, depth_, msAlbedo_, msNormal_;
};

}  // namespace vegstream::render
