// Cascaded sun shadow maps' matrices (shadow_cascades.h).
#include "render/shadow_cascades.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "render/frame_types.h"

namespace vegstream::render {

ShadowCascades shadowCascades(const Camera& camera, double aspect, const glm::dvec3& towardsSun,
                              const ShadowSettings& s) {
  ShadowCascades out;
  const glm::dvec3 l = glm::normalize(towardsSun);
  const glm::dvec3 f = glm::normalize(camera.forward);
  const double ty = std::tan(0.5 * camera.verticalFovDeg * 3.14159265358979323846 / 180.0), tx = ty * aspect;
  // The light's image axes: any pair perpendicular to it (x horizontal unless the sun is overhead).
  glm::dvec3 lx = glm::cross(glm::dvec3(0.0, 0.0, 1.0), l);
  lx = glm::length(lx) > 1e-6 ? glm::normalize(lx) : glm::dvec3(1.0, 0.0, 0.0);
  const glm::dvec3 ly = glm::cross(l, lx);
  double nearD = camera.nearM;
  for (int c = 0; c < kShadowCascades; ++c) {
    const double farD = s.splitsM[size_t(c)];
    // The slice's bounding sphere: its centre on the view axis where the corners' farthest is least.
    const double rn2 = nearD * nearD * (tx * tx + ty * ty), rf2 = farD * farD * (tx * tx + ty * ty);
    double z = 0.5 * (nearD + farD) + 0.5 * (rf2 - rn2) / (farD - nearD);
    z = std::clamp(z, nearD, farD);
    const double radius = std::sqrt(std::max((farD - z) * (farD - z) + rf2, (z - nearD) * (z - nearD) + rn2));
    // Snap the centre to whole texels of the light's image in world coordinates.
    const double texel = 2.0 * radius / static_cast<double>(s.mapSize);
    const glm::dvec3 centreWorld = camera.position + f * z;
    const double cx = std::floor(glm::dot(centreWorld, lx) / texel) * texel;
    const double cy = std::floor(glm::dot(centreWorld, ly) / texel) * texel;
    const glm::dvec3 snapped = lx * cx + ly * cy + l * glm::dot(centreWorld, l);
    const glm::dvec3 centre = snapped - camera.position;  // camera-relative
    const double depthRange = radius + s.casterMarginM;
    glm::dmat4 m(0.0);
    for (int k = 0; k < 3; ++k) {
      m[k][0] = lx[k] / radius;
      m[k][1] = -ly[k] / radius;  // Vulkan's y points down
      m[k][2] = 0.5 * l[k] / depthRange;
    }
    m[3][0] = -glm::dot(centre, lx) / radius;
    m[3][1] = glm::dot(centre, ly) / radius;
    m[3][2] = 0.5 - 0.5 * glm::dot(centre, l) / depthRange;
    m[3][3] = 1.0;
    out.matrices[size_t(c)] = glm::mat4(m);
    out.splits[c] = static_cast<float>(farD);
    out.texelM[size_t(c)] = static_cast<float>(texel);
    nearD = farD;
  }
  out.splits.w = 1.0f;
  return out;
}

}  // namespace vegstream::render
