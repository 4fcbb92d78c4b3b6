// The camera's collider (camera_collider.h): shapes per mode and the placement on the ground.

#include "app/camera_collider.h"

#include <cmath>

namespace vegstream::app {

CameraColliderShape cameraColliderShape(CameraColliderMode mode) {
  switch (mode) {
    case CameraColliderMode::Walking: return {0.35, 1.1, 1.5};  // shoulder-wide, 1.8 m tall: a person
    case CameraColliderMode::Driving:
      return {1.2, 0.5, 3.0};  // 2.4 m wide, 2.9 m tall: a car's width (a vertical capsule has no length)
    case CameraColliderMode::Off: break;
  }
  return {};
}

CameraColliderMode nextCameraColliderMode(CameraColliderMode mode) {
  switch (mode) {
    case CameraColliderMode::Off: return CameraColliderMode::Walking;
    case CameraColliderMode::Walking: return CameraColliderMode::Driving;
    case CameraColliderMode::Driving: break;
  }
  return CameraColliderMode::Off;
}

const char* cameraColliderName(CameraColliderMode mode) {
  switch (mode) {
    case CameraColliderMode::Walking: return "walking";
    case CameraColliderMode::Driving: return "driving";
    case CameraColliderMode::Off: break;
  }
  return "off";
}

std::optional<flight::ColliderSample> cameraCollider(CameraColliderMode mode, const geo::LocalFrame& frame,
                                                     const flight::GroundHeight& ground, const geo::Geodetic& camera,
                                                     double headingDeg) {
  const CameraColliderShape shape = cameraColliderShape(mode);
  if (mode == CameraColliderMode::Off || !ground) return std::nullopt;
  // Ahead in the frame's horizontal plane, the way the fly camera moves (flight::forwardVector
  // at pitch 0). Only the lat/lon of the point ahead is kept: it is then put on the ground along
  // its own vertical, as the camera's ground point is along the camera's, so the height the step
  // is taken at moves both alike (tested 400 m up, 20 km from the frame's origin).
  glm::dvec3 p = frame.toLocal(camera);
  const double h = headingDeg * M_PI / 180.0;
  p.x += std::sin(h) * shape.aheadM;
  p.y += std::cos(h) * shape.aheadM;
  const geo::Geodetic at = frame.toGeodetic(p);
  const double groundM = ground(at.latDeg, at.lonDeg);
  if (!std::isfinite(groundM)) return std::nullopt;
  flight::ColliderSample c;
  c.centre = {at.latDeg, at.lonDeg, groundM + shape.radiusM + 0.5 * shape.lengthM};
  c.radiusM = shape.radiusM;
  c.lengthM = shape.lengthM;
  return c;
}

}  // namespace vegstream::app
