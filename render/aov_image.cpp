// decodeAov (aov_image.h).

#include "render/aov_image.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/packing.hpp>

namespace vegstream::render {

AovImage decodeAov(uint32_t width, uint32_t height, const uint32_t* packed, const float* depth,
                   const glm::dmat4& inverseProjection) {
  assert(packed && depth);
  AovImage a;
  a.width = width;
  a.height = height;
  const size_t pixels = size_t{width} * height;
  a.distanceM.assign(pixels, 0.0f);
  a.coverage.assign(pixels, 0.0f);
  a.species.assign(pixels, 0.0f);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      const size_t i = size_t{y} * width + x;
      const glm::vec3 rgb = glm::unpackF2x11_1x10(packed[i]);
      const float r = rgb.r, g = rgb.g;
      const float covered = std::isfinite(g) ? std::clamp(g, 0.0f, 1.0f) : 0.0f;
      a.coverage[i] = covered;
      a.species[i] = covered > 0.0f && std::isfinite(r) ? std::round(std::max(r, 0.0f) / covered) : 0.0f;
      const float d = depth[i];
      if (!(d > 0.0f)) continue;  // the sky (the far plane is 0 in reverse-Z)
      // The pixel centre in Vulkan's normalised device coordinates (y down, as the rows).
      const glm::dvec4 ndc((2.0 * x + 1.0) / width - 1.0, (2.0 * y + 1.0) / height - 1.0, double(d), 1.0);
      const glm::dvec4 view = inverseProjection * ndc;
      a.distanceM[i] = static_cast<float>(glm::length(glm::dvec3(view) / view.w));
    }
  return a;
}

}  // namespace vegstream::render
