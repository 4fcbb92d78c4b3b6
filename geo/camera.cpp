// The camera's matrices (camera.h).

#include "geo/camera.h"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace vegstream::geo {

glm::dmat4 viewRotation(const Camera& camera) { return glm::lookAtRH(glm::dvec3(0.0), camera.forward, camera.up); }

glm::dmat4 projection(const Camera& camera, double aspect) {
  // Swapping near and far in a [0, 1] depth projection gives reverse-Z.
  glm::dmat4 p = glm::perspectiveRH_ZO(glm::radians(camera.verticalFovDeg), aspect, camera.farM, camera.nearM);
  p[1][1] = -p[1][1];  // Vulkan clip space: y points down
  return p;
}

double reverseZDepth(const Camera& camera, double d) {
  const double n = camera.nearM, f = camera.farM;
  return n * (f - d) / ((f - n) * d);
}

}  // namespace vegstream::geo
