#include "app/fly_camera.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

namespace vegstream::app {
namespace {
double wrapHeading(double deg) {
  double h = std::fmod(deg, 360.0);
  if (h < 0.0) h += 360.0;
  return h >= 360.0 ? 0.0 : h;
}
}  // namespace

FlyCamera::FlyCamera(const geo::LocalFrame& frame, flight::GroundHeight ground, const glm::dvec3& positionEnu,
                     double headingDeg, double pitchDeg, FlyCameraSettings settings)
    : frame_(&frame), ground_(std::move(ground)), settings_(settings), position_(positionEnu),
      headingDeg_(wrapHeading(headingDeg)),
      pitchDeg_(std::clamp(pitchDeg, -settings.maxPitchDeg, settings.maxPitchDeg)),
      speedMps_(std::clamp(settings.speedMps, settings.minSpeedMps, settings.maxSpeedMps)) {
  keepAboveGround();
}

double FlyCamera::groundAt(const geo::Geodetic& g) const {
  const double h = ground_ ? ground_(g.latDeg, g.lonDeg) : 0.0;
  return std::isfinite(h) ? h : 0.0;
}

double FlyCamera::groundBelowM() const { return groundAt(geodetic()); }

void FlyCamera::placeAtHeight(double heightMsl) {
  geo::Geodetic g = geodetic();
  g.heightM = heightMsl;
  position_ = frame_->toLocal(g);
}

void FlyCamera::keepAboveGround() {
  const geo::Geodetic g = geodetic();
  const double minHeight = groundAt(g) + flight::kMinGroundClearanceM;
  if (g.heightM < minHeight) placeAtHeight(minHeight);
}

void FlyCamera::setFollowTerrain(bool on) {
  follow_ = on;
  if (on) followHeightM_ = std::max(heightAboveGroundM(), flight::kMinGroundClearanceM);
}

void FlyCamera::update(const FlyInput& input, double dtS) {
  if (!(dtS > 0.0)) dtS = 0.0;
  // Look first, so this frame's movement goes where the camera now faces.
  headingDeg_ = wrapHeading(headingDeg_ + input.lookDxPx * settings_.degreesPerPixel);
  pitchDeg_ =
      std::clamp(pitchDeg_ - input.lookDyPx * settings_.degreesPerPixel, -settings_.maxPitchDeg, settings_.maxPitchDeg);
  if (input.wheelSteps != 0.0)
    speedMps_ = std::clamp(speedMps_ * std::pow(settings_.wheelFactor, input.wheelSteps), settings_.minSpeedMps,
                           settings_.maxSpeedMps);

  const double speed = speedMps_ * (input.fast ? settings_.fastFactor : 1.0);
  const double h = glm::radians(headingDeg_);
  const glm::dvec3 rightDir{std::cos(h), -std::sin(h), 0.0};  // heading + 90°, horizontal
  const glm::dvec3 before = position_;
  glm::dvec3 move = forward() * input.forward + rightDir * input.right;
  if (!follow_) move.z += input.up;
  const double len = glm::length(move);
  if (len > 1.0) move /= len;  // diagonal keys are not faster
  position_ += move * (speed * dtS);

  if (follow_) {
    followHeightM_ = std::max(followHeightM_ + input.up * speed * dtS, flight::kMinGroundClearanceM);
    placeAtHeight(groundBelowM() + followHeightM_);
  }
  keepAboveGround();
  velocity_ = dtS > 0.0 ? (position_ - before) / dtS : glm::dvec3(0.0);
}

flight::FlightSample FlyCamera::sample() const {
  flight::FlightSample s;
  s.position = geodetic();
  s.headingDeg = headingDeg_;
  s.pitchDeg = pitchDeg_;
  s.velocity = velocity_;
  s.heightAboveGroundM = s.position.heightM - groundAt(s.position);
  return s;
}

}  // namespace vegstream::app
