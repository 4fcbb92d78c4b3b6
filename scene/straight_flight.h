#pragma once
// The foundation's demo flight: a straight line between two geodetic points at a constant
// height above the terrain under the camera, looking ahead and slightly down. Scripted
// keyframed paths (Catmull-Rom, colliders) replace it in the flights issue.

#include "flight/ground_height.h"
#include "geo/local_frame.h"
#include "render/frame_types.h"

namespace vegstream::scene {

using flight::GroundHeight;

struct StraightFlight {
  geo::Geodetic start;  // heightM ignored: the height comes from the terrain
  geo::Geodetic end;
  double altitudeAboveTerrainM = 600.0;
  double durationS = 10.0;
  double pitchDeg = -12.0;  // negative looks down
};

struct FlightPose {
  geo::Geodetic position;  // camera position, height MSL
  render::Camera camera;   // in the local frame
};

// The pose at time t (clamped to [0, duration]). The camera never goes below the ground
// within its look-around radius: it keeps altitudeAboveTerrainM above the highest of a few
// samples around it, so steep canyon walls do not swallow it.
FlightPose poseAt(const StraightFlight& flight, double t, const geo::LocalFrame& frame, const GroundHeight& ground);

}  // namespace vegstream::scene
