#pragma once
// The ROAM error metric and how far it can move, and a node's vertices in eye space (internal
// to the tessellator: roam_priorities.cpp, roam_output.cpp). Seed
// 001_3eca9f2c7752e4fb.txt §3.1 (a screen-space error over nested wedgies); Duchaineau et al.
// 1997 §6 (deferred priority recomputation: how fast a priority can change as the camera moves).
//
// A wedgie of thickness e (vertical) inside a bounding sphere of radius r (grown by e), seen from
// a camera at distance dc from the sphere's centre along a ray at angle θ_c to the vertical,
// spans at most e · sin θ_max · pixelsPerRadian / (dc − r) pixels, sin θ_max = min(1, sin θ_c +
// r / dc) (sin(θ_c + α) ≤ sin θ_c + sin α over the sphere). Distance and angle to the vertical
// are rotation-invariant: only the camera's position moves the error (the rotation moves the
// culling). After the camera moves by m in any direction, dc changes by at most m and the ray
// turns by at most asin(m / dc) plus the turn of the vertical itself (m / the ellipsoid's least
// radius of curvature): upperPx / lowerPx bound the error then.

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "terrain/eye_space.h"
#include "terrain/roam_mesh.h"

namespace vegstream::terrain {

// A vertex in eye space (RoamVertex::at, what culling and priorities use), and a node's three
// (apex, left, right). Inline: the traversals call them for every node they descend through.
inline glm::dvec3 eyeOfVertex(const RoamMesh& mesh, const EyeView& view, uint32_t v) {
  return view.toEye(mesh.vertex(v).at);
}
inline void eyeOf(const RoamMesh& mesh, const EyeView& view, uint32_t t, glm::dvec3* eye) {
  const RoamNode& n = mesh.node(t);
  for (int i = 0; i < 3; ++i) eye[i] = eyeOfVertex(mesh, view, n.v[i]);
}

// The least radius of curvature of the ellipsoid (the meridian's at the equator, rounded down):
// the local up turns by at most 1 / kMinCurvatureRadiusM radians per metre travelled.
inline constexpr double kMinCurvatureRadiusM = 6.3e6;

struct ErrorGeometry {
  double e = 0.0, r = 0.0, dc = 0.0, sinC = 0.0, near = 1.0, pixelsPerRadian = 1.0;

  // For a triangle with eye-space vertices `eye` (apex, left, right): the sphere is centred on the
  // hypotenuse's midpoint (a right triangle's circumcentre) with radius `radius` + thickness.
  static ErrorGeometry of(const EyeView& view, const glm::dvec3* eye, double thickness, double radius) {
    const glm::dvec3 c = 0.5 * (eye[1] + eye[2]);
    const double dc = glm::length(c);
    const double cosC = dc > 0.0 ? std::abs(glm::dot(view.upEye, c)) / dc : 1.0;
    return {thickness,  radius + thickness,  dc, std::sqrt(std::max(0.0, 1.0 - cosC * cosC)),
            view.nearM, view.pixelsPerRadian};
  }
  // The distance from the camera to the sphere (at least the near distance).
  double sphereDistance() const { return std::max(dc - r, near); }
  // How far the ray to the centre can turn, the vertical's own turn included.
  double turn(double moved) const {
    return (moved < dc ? std::asin(moved / dc) : 0.5 * M_PI) + moved / kMinCurvatureRadiusM;
  }
  // The projected error after the camera moved `moved` metres: at most / at least.
  double upperPx(double moved) const {
    const double dcMin = dc - moved;
    const double sinMax = dcMin > r ? std::min(1.0, sinC + (moved > 0.0 ? turn(moved) : 0.0) + r / dcMin) : 1.0;
    return e * sinMax * pixelsPerRadian / std::max(dcMin - r, near);
  }
  double lowerPx(double moved) const {
    const double dcMax = dc + moved;
    const double sinMin = std::min(1.0, std::max(0.0, sinC - turn(moved)) + r / dcMax);
    return e * sinMin * pixelsPerRadian / std::max(dcMax - r, near);
  }
  double errorPx() const { return upperPx(0.0); }
  // The distance the camera may travel before the error may rise above `bound` (rising) or fall
  // below it (falling): the largest of dc / 2, dc / 4, … (down to dc / 2^12) that the bounds
  // allow, else 0. Conservative: the bounds hold for every direction of travel.
  double safeDistance(double bound, bool rising) const {
    double moved = 0.5 * dc;
    for (int i = 0; i < 12; ++i, moved *= 0.5)
      if (rising ? upperPx(moved) <= bound : lowerPx(moved) >= bound) return moved;
    return 0.0;
  }
};

}  // namespace vegstream::terrain
