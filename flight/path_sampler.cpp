#include "flight/path_sampler.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <cstdio>

namespace vegstream::flight {
namespace {

constexpr double kDegToRad = M_PI / 180.0;
constexpr double kVelocityStepS = 1e-3;

std::vector<TrackPoint> cameraPoints(const FlightPath& path) {
  std::vector<TrackPoint> out;
  for (const Keyframe& k : path.keyframes) out.push_back({k.t, k.lat, k.lon, k.altM, k.altRef});
  return out;
}

// The track of a collider's or a wind source's centre (both have ColliderKeyframes: TrackPoints).
PositionTrack objectTrack(const std::vector<ColliderKeyframe>& keys) { return PositionTrack(keys); }

// Where such an object is at t: clamped to its keyframes, no clearance (it may touch the ground).
geo::Geodetic objectCentre(const PositionTrack& track, double t, const GroundHeight& ground) {
  return track.position(t, ground, -INFINITY);
}

std::vector<double> times(const FlightPath& path) {
  std::vector<double> out;
  for (const Keyframe& k : path.keyframes) out.push_back(k.t);
  return out;
}

std::vector<double> unwrappedHeadings(const FlightPath& path) {
  std::vector<double> out;
  for (const Keyframe& k : path.keyframes)
    out.push_back(out.empty() ? k.headingDeg : out.back() + headingDelta(out.back(), k.headingDeg));
  return out;
}

std::vector<double> pitches(const FlightPath& path) {
  std::vector<double> out;
  for (const Keyframe& k : path.keyframes) out.push_back(k.pitchDeg);
  return out;
}

}  // namespace

double headingDelta(double aDeg, double bDeg) {
  double d = std::fmod(bDeg - aDeg, 360.0);  // (−360, 360)
  if (d > 180.0) d -= 360.0;
  if (d <= -180.0) d += 360.0;
  return d;
}

glm::dvec3 forwardVector(double headingDeg, double pitchDeg) {
  const double h = headingDeg * kDegToRad, p = pitchDeg * kDegToRad;
  return {std::cos(p) * std::sin(h), std::cos(p) * std::cos(h), std::sin(p)};
}

PathSampler::PathSampler(const FlightPath& path)
    : camera_(cameraPoints(path)), heading_(times(path), unwrappedHeadings(path)), pitch_(times(path), pitches(path)),
      colliderShapes_(path.colliders) {
  assert(path.keyframes.size() >= 2);
  for (const Collider& c : path.colliders) colliders_.push_back(objectTrack(c.keyframes));
  if (path.wind) {
    windSources_ = path.wind->sources;
    for (const WindSourceSpec& w : windSources_) windTracks_.push_back(objectTrack(w.keyframes));
  }
}

FlightSample PathSampler::sample(double t, const GroundHeight& ground) const {
  t = std::clamp(t, 0.0, duration());
  FlightSample s;
  s.position = camera_.position(t, ground, kMinGroundClearanceM);
  s.heightAboveGroundM = s.position.heightM - groundOrZero(ground, s.position.latDeg, s.position.lonDeg);
  double heading = std::fmod(heading_.value(t), 360.0);
  if (heading < 0.0) heading += 360.0;
  s.headingDeg = heading;
  s.pitchDeg = pitch_.value(t);

  const double t0 = std::max(0.0, t - kVelocityStepS), t1 = std::min(duration(), t + kVelocityStepS);
  if (t1 > t0) {
    const glm::dvec3 a = camera_.frame().toLocal(camera_.position(t0, ground, kMinGroundClearanceM));
    const glm::dvec3 b = camera_.frame().toLocal(camera_.position(t1, ground, kMinGroundClearanceM));
    s.velocity = (b - a) / (t1 - t0);
  }
  return s;
}

ColliderSample PathSampler::collider(std::size_t i, double t, const GroundHeight& ground) const {
  assert(i < colliders_.size());
  const Collider& c = colliderShapes_[i];
  return {objectCentre(colliders_[i], t, ground), c.radiusM, c.shape == Collider::Shape::Capsule ? c.lengthM : 0.0};
}

WindSourceSample PathSampler::windSource(std::size_t i, double t, const GroundHeight& ground) const {
  assert(i < windTracks_.size());
  const WindSourceSpec& w = windSources_[i];
  return {objectCentre(windTracks_[i], t, ground), w.type, w.radiusM, w.strengthMps, w.directionDeg.value_or(0.0)};
}

FlightSample sampleAt(const FlightPath& path, double t, const GroundHeight& ground) {
  return PathSampler(path).sample(t, ground);
}

std::vector<FlightSample> lookAheadSamples(const PathSampler& sampler, const GroundHeight& ground, double timeS,
                                           double horizonS, double stepS) {
  std::vector<FlightSample> out;
  for (double dt = stepS; dt <= horizonS + 1e-9; dt += stepS) {
    const double t = std::min(timeS + dt, sampler.duration());
    out.push_back(sampler.sample(t, ground));
    if (t >= sampler.duration()) break;
  }
  return out;
}

std::size_t frameCount(double durationS, double fps) {
  assert(fps > 0.0 && durationS >= 0.0);
  const double steps = std::floor(durationS * fps + 1e-9);
  if (!(steps < 1e18)) return SIZE_MAX;  // no cast of a value size_t cannot hold
  return static_cast<std::size_t>(steps) + 1;
}

Status checkRecordable(double durationS, double fps, double warmupS, const std::string& sourceName) {
  const std::size_t frames = frameCount(durationS, fps);
  const double warmup = std::round(warmupS * fps);
  if (frames <= kMaxRecordedFrames && warmup <= static_cast<double>(kMaxRecordedFrames - frames)) return {};
  char text[320];
  std::snprintf(text, sizeof(text),
                "%.6g s at %.6g fps is %.6g frames; a recording holds at most %zu (%.4g s at this fps)", durationS, fps,
                std::floor(durationS * fps) + 1.0 + warmup, kMaxRecordedFrames,
                static_cast<double>(kMaxRecordedFrames - 1) / fps);
  return makeError(ErrorKind::InvalidInput, sourceName + ": " + text);
}

}  // namespace vegstream::flight
