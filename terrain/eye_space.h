#pragma once
// The camera as the ROAM traversal sees it (seed 001_3eca9f2c7752e4fb.txt §3.1, "we chose to
// perform the culling operations in eye-space"): the world → eye transform split into a
// rotation and a translation, so that only a split's new vertex is transformed and refined
// triangles' eye coordinates are interpolated (rotations are linear); and a symmetric
// perspective frustum whose planes in eye space are scalar comparisons.
//
// Eye space: x right, y up, looking down −z (as render/camera_math's view matrix).

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

// The wedgie of a triangle with eye-space vertices a, b, c: the prism from `below` metres under
// it to `above` metres over it along the local up. Outside when all six corners are outside
// one plane (near, left, right, bottom, top); Inside when all are inside all planes.
// (Defined below, inline: the traversals call it for every node.)
inline Cull cullWedgie(const EyeView& view, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, double below,
                       double above);

// The same test split in two, for many triangles sharing vertices (a drawn chunk culled
// triangle by triangle): each vertex's signed distances to the five planes once, then per
// triangle only the comparisons, plane by plane. wedgieOutsidePlane(..., k) for any k being
// true == (cullWedgie(...) == Cull::Outside), bit for bit: the same arithmetic in the same order.
struct PlaneDistances {
  double d[5];  // near, left, right, bottom, top (n·q + d ≥ 0 inside)
};
inline PlaneDistances planeDistances(const EyeView& view, const glm::dvec3& q) {
  const double tx = view.tanHalfX, ty = view.tanHalfY;
  return {{-q.z - view.nearM, q.x - tx * q.z, -q.x - tx * q.z, q.y - ty * q.z, -q.y - ty * q.z}};
}
// The up direction's component along each plane normal (the plane offsets do not apply to it).
inline PlaneDistances upComponents(const EyeView& view) {
  const double tx = view.tanHalfX, ty = view.tanHalfY;
  const glm::dvec3& u = view.upEye;
  return {{-u.z, u.x - tx * u.z, -u.x - tx * u.z, u.y - ty * u.z, -u.y - ty * u.z}};
}
// Whether the prism lies wholly outside plane k.
inline bool wedgieOutsidePlane(const PlaneDistances& a, const PlaneDistances& b, const PlaneDistances& c,
                               const PlaneDistances& up, double below, double above, int k) {
  const double s = -below * up.d[k], t = above * up.d[k];
  const double hi = s > t ? s : t;
  double m = a.d[k] > b.d[k] ? a.d[k] : b.d[k];
  m = m > c.d[k] ? m : c.d[k];
  return m + hi < 0.0;
}

inline Cull cullWedgie(const EyeView& view, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, double below,
                       double above) {
  // The planes in eye space (n·q + d ≥ 0 inside): near −z − near, left x − tx·z, right −x − tx·z,
  // bottom y − ty·z, top −y − ty·z.
  const PlaneDistances da = planeDistances(view, a), db = planeDistances(view, b), dc = planeDistances(view, c);
  const PlaneDistances nu = upComponents(view);
  bool inside = true;
  for (int k = 0; k < 5; ++k) {
    // The prism's corners v + s·up for s in {−below, +above}: extremes per vertex.
    const double s = -below * nu.d[k], t = above * nu.d[k];
    const double lo = s < t ? s : t, hi = s > t ? s : t;
    double mx = da.d[k] > db.d[k] ? da.d[k] : db.d[k], mn = da.d[k] < db.d[k] ? da.d[k] : db.d[k];
    mx = mx > dc.d[k] ? mx : dc.d[k];
    mn = mn < dc.d[k] ? mn : dc.d[k];
    if (mx + hi < 0.0) return Cull::Outside;
    if (mn + lo < 0.0) inside = false;
  }
  return inside ? Cull::Inside : Cull::Partial;
}

}  // namespace vegstream::terrain
