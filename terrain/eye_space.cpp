// Eye-space culling of ROAM wedgies (eye_space.h); seed 001_3eca9f2c7752e4fb.txt §3.1.

#include "terrain/eye_space.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/geometric.hpp>

namespace vegstream::terrain {

EyeView EyeView::lookAlong(const glm::dvec3& position, const glm::dvec3& forward, const glm::dvec3& up,
                           double verticalFovRad, double widthPx, double heightPx, double nearM) {
  EyeView v;
  v.cameraEnu = position;
  const glm::dvec3 f = glm::normalize(forward);
  const glm::dvec3 r = glm::normalize(glm::cross(f, up));
  const glm::dvec3 u = glm::cross(r, f);
  // Rows: eye x = r·d, y = u·d, z = −f·d (glm is column-major: m[col][row]).
  glm::dmat3 m;
  for (int i = 0; i < 3; ++i) {
    m[i][0] = r[i];
    m[i][1] = u[i];
    m[i][2] = -f[i];
  }
  v.rotation = m;
  v.upEye = m * glm::normalize(up);
  v.tanHalfY = std::tan(0.5 * verticalFovRad);
  v.tanHalfX = v.tanHalfY * widthPx / heightPx;
  v.nearM = nearM;
  v.viewportWidthPx = widthPx;
  v.viewportHeightPx = heightPx;
  v.pixelsPerRadian = heightPx / (2.0 * v.tanHalfY);
  return v;
}

}  // namespace vegstream::terrain
