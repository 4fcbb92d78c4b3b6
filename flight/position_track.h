#pragma once
// A geodetic position over time through keyframes (t, lat, lon, altitude + its reference),
// shared by the camera path and the scripted colliders.
//
// Horizontal: a centripetal Catmull-Rom spline (catmull_rom.h) through the keyframes' points
// on the ellipsoid, expressed in an ENU frame at the first keyframe, so distances are metric
// and the curve is the same anywhere on earth. Its knot parameter s is mapped to time by a
// monotone cubic through (t_i, s_i): position(t) = CR(s(t)) is C¹ in time (a composition of C¹
// maps) and passes through keyframe i exactly at t_i, while the curve's shape stays the
// centripetal one (no cusps, no loops at sharp turns).
//
// Vertical: altitude a(t) and a terrain weight w(t) (1 for "terrain" keyframes, 0 for "msl")
// are monotone cubics in time (no overshoot: a dive to 15 m never dips below 15 m), and the
// height is a(t) + w(t)·ground(lat, lon), so each keyframe's altitude holds in its own
// reference and mixed references blend smoothly. The result is then kept at least
// minClearanceM above the ground under the point.

#include <optional>
#include <vector>

#include "flight/catmull_rom.h"
#include "flight/flight_path.h"
#include "flight/ground_height.h"
#include "flight/monotone_cubic.h"
#include "geo/geodetic.h"
#include "geo/local_frame.h"

namespace vegstream::flight {

// A point of a track: time, lat/lon, altitude and its reference. A collider's or a wind source's
// keyframe is one as it is; a camera keyframe is one plus its heading and pitch.
using TrackPoint = ColliderKeyframe;

class PositionTrack {
 public:
  // points non-empty, t strictly increasing (asserted). One point = a fixed position.
  explicit PositionTrack(const std::vector<TrackPoint>& points);

  // The lat/lon at time t (clamped to the keyframes' span); heightM = 0.
  geo::Geodetic horizontal(double t) const;
  // The full position, height MSL: altitude resolved against the ground (NaN = 0) and kept
  // at least minClearanceM above it (pass -infinity for no clearance).
  geo::Geodetic position(double t, const GroundHeight& ground, double minClearanceM) const;

  const geo::LocalFrame& frame() const { return frame_; }
  double startT() const { return times_.front(); }
  double endT() const { return times_.back(); }

 private:
  std::vector<double> times_;
  geo::LocalFrame frame_;
  std::optional<CentripetalCatmullRom> curve_;  // absent for a single point
  std::optional<MonotoneCubic> knotOfTime_;
  glm::dvec3 single_{0.0};
  MonotoneCubic alt_;
  MonotoneCubic terrainWeight_;
};

// The ground under a point, NaN read as 0 (sea level).
double groundOrZero(const GroundHeight& ground, double lat, double lon);

}  // namespace vegstream::flight
