#pragma once
// A collider that follows the window's camera (issue 19), so the user can push through the grass
// and see the trail it leaves: C cycles off → walking → driving → off. Walking is a person-sized
// vertical capsule 1.5 m ahead of the camera's ground point along its heading; driving a low,
// wide one 3 m ahead, about a car's width. Either stands on the ground, whatever the camera's
// height, so flying high still shows where it walks. Pure geometry (no GLFW, no scene), so the
// placement is unit-tested; the window passes it to the frame driver with the path's colliders.

#include <optional>

#include "flight/ground_height.h"
#include "flight/path_sampler.h"
#include "geo/local_frame.h"

namespace vegstream::app {

enum class CameraColliderMode { Off, Walking, Driving };

struct CameraColliderShape {
  double radiusM = 0.0;
  double lengthM = 0.0;  // between the end-cap centres (flight::ColliderSample::lengthM)
  double aheadM = 0.0;   // horizontal distance ahead of the camera's ground point
};

// The shape of each mode (Off: all zero).
CameraColliderShape cameraColliderShape(CameraColliderMode mode);
// What C switches to: off → walking → driving → off.
CameraColliderMode nextCameraColliderMode(CameraColliderMode mode);
// "off", "walking", "driving" (the HUD and the log).
const char* cameraColliderName(CameraColliderMode mode);

// The collider for a camera at `camera` (height MSL, ignored) looking along `headingDeg`
// (clockwise from north of `frame`, as the fly camera's heading is): its centre is aheadM
// ahead in the frame's horizontal plane, at ground(lat, lon) + radius + length / 2 there, so
// the capsule's bottom touches the ground. Empty when the mode is Off or the ground is unknown
// there (NaN: outside the dataset; nothing to push).
std::optional<flight::ColliderSample> cameraCollider(CameraColliderMode mode, const geo::LocalFrame& frame,
                                                     const flight::GroundHeight& ground, const geo::Geodetic& camera,
                                                     double headingDeg);

}  // namespace vegstream::app
