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

Cull cullWedgie(const EyeView& view, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, double below,
                double above) {
  // Inward plane normals in eye space (n·q + d ≥ 0 inside).
  const std::array<glm::dvec4, 5> planes{{
      {0.0, 0.0, -1.0, -view.nearM},
      {1.0, 0.0, -view.tanHalfX, 0.0},
      {-1.0, 0.0, -view.tanHalfX, 0.0},
      {0.0, 1.0, -view.tanHalfY, 0.0},
      {0.0, -1.0, -view.tanHalfY, 0.0},
  }};
  bool inside = true;
  for (const glm::dvec4& p : planes) {
    const glm::dvec3 n(p);
    const double nu = glm::dot(n, view.upEye);
    // The prism's corners v + s·up for s in {−below, +above}: extremes per vertex.
    const double lo = std::min(-below * nu, above * nu), hi = std::max(-below * nu, above * nu);
    const double da = glm::dot(n, a) + p.w, db = glm::dot(n, b) + p.w, dc = glm::dot(n, c) + p.w;
    if (std::max({da, db, dc}) + hi < 0.0) return Cull::Outside;
    if (std::min({da, db, dc}) + lo < 0.0) inside = false;
  }
  return inside ? Cull::Inside : Cull::Partial;
}

}  // namespace vegstream::terrain
