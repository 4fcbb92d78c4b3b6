#pragma once
// Internal to the tree pass (tree_pass.cpp: pipelines, classify, draws; tree_models.cpp: the
// models' upload, the draw templates and the impostor capture): the GPU blocks the shaders read
// and the constants both halves use. Not part of the renderer's interface (tree_pass.h is).

#include <cstddef>
#include <cstdint>

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include "render/pipeline_builder.h"
#include "render/tree_layout.h"
#include "vegetation/tree_model.h"

namespace vegstream::render::tree_detail {

// shaders/common/tree_layout.glsl's TreeModelGpu and TreeBlock (std140: vec4 members only).
struct TreeModelGpu {
  glm::uvec4 mesh0, mesh1;
  glm::vec4 shape, leaf, bark;
  glm::vec4 triangleApex, triangleBase;  // the impostor's triangle per elevation bin (tree_impostor_outline.h)
  glm::uvec4 ids;  // x: the species (catalog index: the AOV frames' species), y: crown area radius (float bits)
};
struct TreeBlock {
  glm::vec4 camera, lod;
  glm::vec4 frustum[6];
  glm::uvec4 counts, capacity;
  glm::vec4 limits;
  glm::uvec4 casters;  // xyz: shadow caster entries per model in each cascade
  TreeModelGpu models[kMaxTreeModels];
};
static_assert(sizeof(TreeModelGpu) == 128);
static_assert(offsetof(TreeBlock, counts) == 128);
static_assert(offsetof(TreeBlock, models) == 192);

// shaders/common/tree_push.glsl.
struct TreePush {
  glm::mat4 capture;
  uint32_t model, lod, mode, samples;
};
static_assert(sizeof(TreePush) == 80);

// The counters (shaders/common/tree_layout.glsl): 0 instances, 1–3 appended per level, 4 dropped,
// 5–7 shadow casters per cascade.
inline constexpr uint32_t kCounters = 8;
// The impostors' one triangle (render/tree_impostor_outline.h), at the index buffer's start.
inline constexpr uint32_t kImpostorIndices = 3;
inline constexpr VkDeviceSize kIndexedCommand = 5 * sizeof(uint32_t);
inline constexpr uint32_t kMaxPages = 4096;  // 1 Mi trees: far more than a 3 km horizon holds

// vegetation::TreeVertex as the vertex stage reads it (shaders/tree.vert's locations 0–6).
inline void setTreeVertexInput(GraphicsPipelineDesc& desc) {
  desc.bindings = {{0, sizeof(vegetation::TreeVertex), VK_VERTEX_INPUT_RATE_VERTEX}};
  desc.attributes = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, 0},  {1, 0, VK_FORMAT_R32_UINT, 12},
                     {2, 0, VK_FORMAT_R32G32B32_SFLOAT, 16}, {3, 0, VK_FORMAT_R32_SFLOAT, 28},
                     {4, 0, VK_FORMAT_R32G32_SFLOAT, 32},    {5, 0, VK_FORMAT_R32_UINT, 40},
                     {6, 0, VK_FORMAT_R32_SFLOAT, 44}};
}

}  // namespace vegstream::render::tree_detail
