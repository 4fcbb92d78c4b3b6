#pragma once
// The interactive fly camera: a double-precision position in the scene's ENU frame, heading
// and pitch, moved by plain input numbers (no GLFW here, so the maths is unit-tested without a
// window). W/S fly along the view direction, A/D strafe horizontally, Q/E go down/up; the mouse
// turns (pitch clamped to ±89°); the wheel scales the speed; Shift multiplies it. Follow-terrain
// keeps a fixed height above the ground; in every mode the camera stays at least
// flight::kMinGroundClearanceM above it.

#include <glm/vec3.hpp>

#include "flight/ground_height.h"
#include "flight/path_sampler.h"
#include "geo/local_frame.h"

namespace vegstream::app {

// One frame's input, already decoded from keys and mouse.
struct FlyInput {
  double forward = 0.0;     // +1 W, −1 S
  double right = 0.0;       // +1 D, −1 A
  double up = 0.0;          // +1 E, −1 Q
  bool fast = false;        // Shift
  double lookDxPx = 0.0;    // mouse movement while looking (pixels, +x right)
  double lookDyPx = 0.0;    // (+y down: moving the mouse down looks down)
  double wheelSteps = 0.0;  // +1 per notch up (faster)
};

struct FlyCameraSettings {
  double speedMps = 80.0;
  double minSpeedMps = 1.0;
  double maxSpeedMps = 20'000.0;
  double fastFactor = 5.0;
  double wheelFactor = 1.25;      // speed × this per wheel notch
  double degreesPerPixel = 0.15;  // mouse-look sensitivity
  double maxPitchDeg = 89.0;
};

class FlyCamera {
 public:
  // `frame` and `ground` must outlive the camera (the scene's). NaN ground counts as 0 m.
  FlyCamera(const geo::LocalFrame& frame, flight::GroundHeight ground, const glm::dvec3& positionEnu, double headingDeg,
            double pitchDeg, FlyCameraSettings settings = {});

  // Advances by dt seconds of input.
  void update(const FlyInput& input, double dtS);

  // Follow-terrain: on, it keeps the current height above the ground (Q/E change that height).
  void setFollowTerrain(bool on);
  bool followTerrain() const { return follow_; }
  double followHeightM() const { return followHeightM_; }

  const glm::dvec3& position() const { return position_; }  // ENU, metres
  double headingDeg() const { return headingDeg_; }         // [0, 360)
  double pitchDeg() const { return pitchDeg_; }
  double speedMps() const { return speedMps_; }
  glm::dvec3 forward() const { return flight::forwardVector(headingDeg_, pitchDeg_); }
  geo::Geodetic geodetic() const { return frame_->toGeodetic(position_); }
  double groundBelowM() const;  // ground height (m MSL) under the camera, 0 where unknown
  double heightAboveGroundM() const { return geodetic().heightM - groundBelowM(); }

  // The pose as a flight sample (what Scene::frameRequest and the path recorder take).
  flight::FlightSample sample() const;

 private:
  double groundAt(const geo::Geodetic& g) const;
  void placeAtHeight(double heightMsl);  // same lat/lon, new height
  void keepAboveGround();

  const geo::LocalFrame* frame_;
  flight::GroundHeight ground_;
  FlyCameraSettings settings_;
  glm::dvec3 position_;
  glm::dvec3 velocity_{0.0};
  double headingDeg_;
  double pitchDeg_;
  double speedMps_;
  bool follow_ = false;
  double followHeightM_ = 0.0;
};

}  // namespace vegstream::app
