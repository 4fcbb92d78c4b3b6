// frameUniforms (frame_uniforms.h): the per-frame constants every pass reads.

#include "render/frame_uniforms.h"

#include <algorithm>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "render/atmosphere_pass.h"
#include "render/frame_types.h"
#include "render/shadow_cascades.h"
#include "render/terrain_detail.h"

namespace vegstream::render {

FrameUniforms frameUniforms(const FrameRequest& request, uint32_t width, uint32_t height,
                            const ShadowCascades* shadows) {
  const double aspect = static_cast<double>(width) / static_cast<double>(height);
  const glm::dmat4 viewProj = projection(request.camera, aspect) * viewRotation(request.camera);
  FrameUniforms u{};
  u.viewProj = glm::mat4(viewProj);
  u.invViewProj = glm::mat4(glm::inverse(viewProj));
  u.sunDirection = glm::vec4(glm::vec3(glm::normalize(request.lighting.sunDirection)), 0.0f);
  u.atmosphere = glm::vec4(atmosphereCameraRadiusKm(request.cameraHeightMsl), kAerialFarKm, 0.0f, 0.0f);
  u.viewport = glm::vec4(static_cast<float>(width), static_cast<float>(height), 1.0f / static_cast<float>(width),
                         1.0f / static_cast<float>(height));
  // World-anchored detail tiling: the camera position modulo the period, in double, so the
  // shader's coordinates stay small and continuous (the repeat counts are whole per period).
  const glm::dvec3 wrapped =
      request.camera.position - kDetailPeriodM * glm::floor(request.camera.position / kDetailPeriodM);
  u.detail = glm::vec4(glm::vec3(wrapped), std::clamp(request.terrainDetail, 0.0f, 1.0f));
  if (shadows) {
    for (int c = 0; c < kShadowCascades; ++c) u.shadowMatrices[c] = shadows->matrices[size_t(c)];
    u.shadowSplits = shadows->splits;
    u.shadowTexel = glm::vec4(shadows->texelM[0], shadows->texelM[1], shadows->texelM[2], float(shadows->drawn));
  }
  u.outputs = glm::vec4(request.aov ? 1.0f : 0.0f, 0.0f, 0.0f, 0.0f);
  return u;
}

}  // namespace vegstream::render
