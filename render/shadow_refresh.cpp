#include "render/shadow_refresh.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace vegstream::render {

uint32_t ShadowRefresh::plan(ShadowCascades& cascades, const glm::dvec3& camera, const glm::dvec3& towardsSun,
                             uint64_t frame) {
  // The sun turned (more than about 0.03°): every layer is drawn again.
  if (glm::dot(glm::normalize(towardsSun), sun_) < 0.9999998) drawn_ = {};
  sun_ = glm::normalize(towardsSun);
  uint32_t mask = 0;
  for (int c = 0; c < kShadowCascades; ++c) {
    Drawn& d = drawn_[size_t(c)];
    // A camera that moved more than a twentieth of the slice's reach since (a jump, not a flight).
    const double moved = glm::length(camera - d.camera);
    const uint64_t phase = frame % 4;  // 0: cascade 0, 1: cascade 1, 2: cascade 0, 3: cascade 2
    const bool turn = c == 0 ? phase % 2 == 0 : phase == uint64_t(2 * c - 1);
    if (turn || !d.valid || moved > 0.05 * double(cascades.splits[c])) {
      mask |= 1u << c;
      d = {true, camera, cascades.matrices[size_t(c)]};
    } else {
      cascades.matrices[size_t(c)] = d.matrix * glm::translate(glm::mat4(1.0f), glm::vec3(camera - d.camera));
    }
  }
  cascades.drawn = mask;
  return mask;
}

}  // namespace vegstream::render
