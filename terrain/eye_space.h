#pragma once
// The camera as the ROAM traversal sees it (seed 001_3eca9f2c7752e4fb.txt §3.1, "we chose to
// perform the culling operations in eye-space"): the world → eye transform split into a
// rotation and a translation, so that only a split's new vertex is transformed and refined
// triangles' eye coordinates are interpolated (rotations are linear); and a symmetric
// perspective frustum whose planes in eye space are scalar comparisons.
//
// Eye space: x right, y up, looking down −z (as render/camera_math's view matrix).

#include <bit>
#include <cstdint>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

namespace vegstream::terrain {

enum class Cull { Outside, Partial, Inside };

struct EyeView {
  glm::dvec3 cameraEnu{0.0};
  glm::dmat3 rotation{1.0};         // ENU directions → eye
  glm::dvec3 upEye{0.0, 1.0, 0.0};  // the local up at the camera, in eye space
  double tanHalfX = 1.0, tanHalfY = 1.0;
  double nearM = 1.0;
  double pixelsPerRadian = 1000.0;  // viewport height / (2 tan(fovY / 2))
  double viewportWidthPx = 1920.0, viewportHeightPx = 1080.0;

  // A camera at `position` looking along `forward` with `up` roughly up; vertical field of view.
  static EyeView lookAlong(const glm::dvec3& position, const glm::dvec3& forward, const glm::dvec3& up,
                           double verticalFovRad, double widthPx, double heightPx, double nearM);

  glm::dvec3 rotate(const glm::dvec3& enuOffset) const { return rotation * enuOffset; }
  glm::dvec3 toEye(const glm::dvec3& enu) const { return rotation * (enu - cameraEnu); }
};

// The frustum planes a wedgie straddles: bit k for plane k (near, left, right, bottom, top).
// Hierarchical culling hands them down the bintree: a wedgie lies inside its parent's (the
// thicknesses nest, roam_mesh.h), so it is wholly inside every plane its parent's is wholly
// inside, and only the planes the parent straddled are tested again — at most nodes one of five.
using PlaneMask = uint8_t;
inline constexpr PlaneMask kEveryPlane = 0x1F;

// The five planes as coefficients, made once per traversal: a distance is then three products
// and three sums, the same for every plane (a switch over the planes, an indirect jump for every
// plane of every vertex whose target changes from node to node, was a fifth of the priority
// traversal's instructions). In eye space (n·q + d ≥ 0 inside): near −z − near, left x − tx·z,
// right −x − tx·z, bottom y − ty·z, top −y − ty·z.
struct Frustum {
  double nx[5], ny[5], nz[5], d[5];
  double up[5];  // the local up's component along each normal (offsets do not apply to it)

  explicit Frustum(const EyeView& view)
      : nx{0.0, 1.0, -1.0, 0.0, 0.0},
        ny{0.0, 0.0, 0.0, 1.0, -1.0},
        nz{-1.0, -view.tanHalfX, -view.tanHalfX, -view.tanHalfY, -view.tanHalfY},
        d{-view.nearM, 0.0, 0.0, 0.0, 0.0} {
    for (int k = 0; k < 5; ++k) up[k] = nx[k] * view.upEye.x + ny[k] * view.upEye.y + nz[k] * view.upEye.z;
  }
  double distance(const glm::dvec3& q, int k) const { return nx[k] * q.x + ny[k] * q.y + nz[k] * q.z + d[k]; }
};

// The wedgie of a triangle with eye-space vertices a, b, c: the prism from `below` metres under
// it to `above` metres over it along the local up. Outside when all six corners are outside
// one plane (near, left, right, bottom, top); Inside when all are inside all planes. Against
// the planes in `planes` only (the others known to hold the prism wholly inside): `planes`
// becomes those the prism straddles (none when Inside; unchanged when Outside). In plane order,
// so that the first plane the prism is wholly outside decides, whatever the mask.
inline Cull cullWedgie(const Frustum& f, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, double below,
                       double above, PlaneMask& planes) {
  PlaneMask straddled = 0;
  for (PlaneMask m = planes; m != 0; m = static_cast<PlaneMask>(m & (m - 1))) {
    const int k = std::countr_zero(m);
    // The prism's corners v + s·up for s in {−below, +above}: extremes per vertex.
    const double s = -below * f.up[k], t = above * f.up[k];
    const double lo = s < t ? s : t, hi = s > t ? s : t;
    const double da = f.distance(a, k), db = f.distance(b, k), dc = f.distance(c, k);
    double mx = da > db ? da : db, mn = da < db ? da : db;
    mx = mx > dc ? mx : dc;
    mn = mn < dc ? mn : dc;
    if (mx + hi < 0.0) return Cull::Outside;
    if (mn + lo < 0.0) straddled = static_cast<PlaneMask>(straddled | (1u << k));
  }
  planes = straddled;
  return straddled == 0 ? Cull::Inside : Cull::Partial;
}
// Against every plane.
inline Cull cullWedgie(const Frustum& f, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, double below,
                       double above) {
  PlaneMask planes = kEveryPlane;
  return cullWedgie(f, a, b, c, below, above, planes);
}
// The same for a test of one wedgie (the traversals make their Frustum once).
inline Cull cullWedgie(const EyeView& view, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, double below,
                       double above) {
  return cullWedgie(Frustum(view), a, b, c, below, above);
}


}  // namespace vegstream::terrain
