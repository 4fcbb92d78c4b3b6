#pragma once
// The camera pose (and collider and wind-source positions) of a FlightPath at any flight time: geodetic
// position, heading and pitch, independent of the renderer's camera type. Position follows
// position_track.h (centripetal Catmull-Rom, C¹ in time, altitude in its own reference, never
// below the ground). Heading is unwrapped (each step taken the short way, in (−180, 180]) and
// interpolated, like pitch, with a monotone cubic (monotone_cubic.h): C¹, no overshoot, so a
// turn from 170° to −170° passes through 180°, not 0°.

#include <cstddef>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "core/result.h"
#include "flight/flight_path.h"
#include "flight/ground_height.h"
#include "flight/monotone_cubic.h"
#include "flight/position_track.h"
#include "geo/geodetic.h"

namespace vegstream::flight {

// The camera never comes closer than this to the ground under it (MSL keyframes included).
inline constexpr double kMinGroundClearanceM = 2.0;

struct FlightSample {
  geo::Geodetic position;    // height MSL
  double headingDeg = 0.0;   // [0, 360), 0 = north, clockwise
  double pitchDeg = 0.0;     // negative looks down
  glm::dvec3 velocity{0.0};  // m/s in the ENU frame at the path's first keyframe (central difference)
  double heightAboveGroundM = 0.0;
};

struct ColliderSample {
  geo::Geodetic centre;  // height MSL (a capsule's middle; its axis is vertical)
  double radiusM = 0.0;
  double lengthM = 0.0;
};

struct WindSourceSample {
  geo::Geodetic centre;  // height MSL (a rotor's hub)
  WindSourceSpec::Type type = WindSourceSpec::Type::Fan;
  double radiusM = 0.0;
  double strengthMps = 0.0;
  double directionDeg = 0.0;  // fan: where it blows towards, clockwise from north; 0 when absent
};

// Built once per path (precomputes the splines); sampling is then cheap and const.
class PathSampler {
 public:
  // The path must be valid (findProblem(path) empty; asserted on counts and time order).
  explicit PathSampler(const FlightPath& path);

  double duration() const { return camera_.endT(); }
  // t is clamped to [0, duration()]. Calls ground 3 times (position and velocity).
  FlightSample sample(double t, const GroundHeight& ground) const;
  // lat/lon only, no ground needed (bounds checks).
  geo::Geodetic horizontal(double t) const { return camera_.horizontal(t); }
  // Collider i at time t (clamped to its keyframes); no clearance: colliders touch the ground.
  ColliderSample collider(std::size_t i, double t, const GroundHeight& ground) const;
  std::size_t colliderCount() const { return colliders_.size(); }
  // Wind source i of the path's wind section at time t: positioned exactly as a collider with
  // the same keyframes would be (clamped to its keyframes, no clearance).
  WindSourceSample windSource(std::size_t i, double t, const GroundHeight& ground) const;
  std::size_t windSourceCount() const { return windTracks_.size(); }
  // The ENU frame that FlightSample::velocity is expressed in.
  const geo::LocalFrame& frame() const { return camera_.frame(); }

 private:
  PositionTrack camera_;
  MonotoneCubic heading_;  // unwrapped degrees
  MonotoneCubic pitch_;
  std::vector<PositionTrack> colliders_;
  std::vector<Collider> colliderShapes_;
  std::vector<PositionTrack> windTracks_;
  std::vector<WindSourceSpec> windSources_;  // type, radius, strength, direction of each track
};

// One-off convenience: builds a PathSampler and samples it once.
FlightSample sampleAt(const FlightPath& path, double t, const GroundHeight& ground);

// Unit view direction in ENU (x = east, y = north, z = up) for a heading and pitch in degrees.
glm::dvec3 forwardVector(double headingDeg, double pitchDeg);

// Heading difference b − a wrapped to (−180, 180].
double headingDelta(double aDeg, double bDeg);

// Look-ahead poses of a scripted path: the samples at t + stepS, t + 2·stepS, …, t + horizonS
// (clamped to the end, which ends the list). The streamer requests their tiles early.
std::vector<FlightSample> lookAheadSamples(const PathSampler& sampler, const GroundHeight& ground, double timeS,
                                           double horizonS = 3.0, double stepS = 0.5);

// Frames of a fixed-step playback at `fps`: t = 0, 1/fps, … up to and including the path's end.
// Saturates at SIZE_MAX (a path the validator allows, t ≤ 10⁹ s, at a high fps).
std::size_t frameCount(double durationS, double fps);

// The most frames one recording holds. A recording keeps every frame's figures in memory until
// its tables are written (a few hundred bytes a frame, reserved up front), so this ceiling —
// 4.6 hours at 60 fps, about 1 GB of figures at most — is checked before anything is reserved:
// a longer path is refused in one line, not recorded in pieces.
inline constexpr std::size_t kMaxRecordedFrames = 1'000'000;
// InvalidInput naming `sourceName` when a path of `durationS` at `fps` (warm-up included) is
// more frames than kMaxRecordedFrames.
Status checkRecordable(double durationS, double fps, double warmupS, const std::string& sourceName);

}  // namespace vegstream::flight
