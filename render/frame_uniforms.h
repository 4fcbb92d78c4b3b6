#pragma once
// C++ mirror of shaders/common/frame_uniforms.glsl (std140). Only vec4/mat4 members, so the
// std140 layout equals the C++ layout; the static_asserts keep the two in step.

#include <cstddef>
#include <cstdint>

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

namespace vegstream::render {

struct FrameUniforms {
  glm::mat4 viewProj;
  glm::mat4 invViewProj;
  glm::vec4 sunDirection;
  glm::vec4 atmosphere;  // x: the camera's radius (km), y: the aerial volume's far distance (km) (render/atmosphere_pass.h)
  glm::vec4 viewport;
  glm::vec4 detail;  // xyz: camera position modulo kDetailPeriodM (render/terrain_detail.h), w: detail strength
  glm::mat4 shadowMatrices[3];  // render/shadow_cascades.h
  glm::vec4 shadowSplits;       // xyz: cascades' far distances, w: 1 when shadows are drawn this frame
  glm::vec4 shadowTexel;        // xyz: cascades' texel sizes (m), w: ShadowCascades::drawn (the cascades drawn this frame)
  // x: 1 when the terrain was rasterised in compute (its depth samples, set 0 binding 5, are
  // written into the depth attachment: shaders/terrain_depth.frag); y: samples per pixel; z: 1
  // when the Hi-Z pyramid (set 0 binding 6) holds this frame's terrain before the trees' scope
  // (shaders/common/hiz_occlusion.glsl).
  glm::vec4 terrainDepth;
  // x: 1 in an AOV frame (FrameRequest::aov, shaders/common/aov.glsl): the passes write
  // vegetation coverage and species instead of colour.
  glm::vec4 outputs;
};

static_assert(offsetof(FrameUniforms, viewProj) == 0);
static_assert(offsetof(FrameUniforms, invViewProj) == 64);
static_assert(offsetof(FrameUniforms, sunDirection) == 128);
static_assert(offsetof(FrameUniforms, atmosphere) == 144);
static_assert(offsetof(FrameUniforms, viewport) == 160);
static_assert(offsetof(FrameUniforms, detail) == 176);
static_assert(offsetof(FrameUniforms, shadowMatrices) == 192);
static_assert(offsetof(FrameUniforms, shadowSplits) == 384);
static_assert(offsetof(FrameUniforms, terrainDepth) == 416);
static_assert(offsetof(FrameUniforms, outputs) == 432);
static_assert(sizeof(FrameUniforms) == 448);

struct FrameRequest;
struct ShadowCascades;

// The frame's uniforms: everything relative to the camera, rotation-only view, for a target of
// width × height pixels.
// `shadows`: this frame's sun shadow cascades, or null (no shadow map: everything sunlit).
FrameUniforms frameUniforms(const FrameRequest& request, uint32_t width, uint32_t height,
                            const ShadowCascades* shadows = nullptr);

}  // namespace vegstream::render
