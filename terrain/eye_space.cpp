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
  // The planes in eye space (n·q + d ≥ 0 inside): near −z − near, left x − tx·z, right −x − tx·z,
  // bottom y − ty·z, top −y − ty·z. Written out: the traversals call this for every node.
  const double tx = view.tanHalfX, ty = view.tanHalfY;
  const glm::dvec3& u = view.upEye;
  auto planes = [&](const glm::dvec3& q, double* d) {
    d[0] = -q.z - view.nearM;
    d[1] = q.x - tx * q.z;
    d[2] = -q.x - tx * q.z;
    d[3] = q.y - ty * q.z;
    d[4] = -q.y - ty * q.z;
  };
  double da[5], db[5], dc[5], nu[5];
  planes(a, da);
  planes(b, db);
  planes(c, dc);
  // The up direction's component along each normal (the plane offsets do not apply to it).
  nu[0] = -u.z;
  nu[1] = u.x - tx * u.z;
  nu[2] = -u.x - tx * u.z;
  nu[3] = u.y - ty * u.z;
  nu[4] = -u.y - ty * u.z;
  bool inside = true;
  for (int k = 0; k < 5; ++k) {
    // The prism's corners v + s·up for s in {−below, +above}: extremes per vertex.
    const double lo = std::min(-below * nu[k], above * nu[k]), hi = std::max(-below * nu[k], above * nu[k]);
    if (std::max({da[k], db[k], dc[k]}) + hi < 0.0) return Cull::Outside;
    if (std::min({da[k], db[k], dc[k]}) + lo < 0.0) inside = false;
  }
  return inside ? Cull::Inside : Cull::Partial;
}

}  // namespace vegstream::terrain
