#pragma once
// A scripted flight path: camera keyframes (time, geodetic position, altitude above the
// terrain or above sea level, heading, pitch), optional scripted colliders (moving spheres
// and capsules with their own keyframes) that the interaction issue pushes plants with, and an
// optional wind section (issue 19: mean wind, gustiness, moving local wind sources).
// The data model and its checks live here; JSON reading/writing is in flight_path_json.h,
// interpolation in path_sampler.h (DESIGN.md "Flight paths").

#include <optional>
#include <string>
#include <vector>

#include "core/result.h"
#include "geo/bounds.h"
#include "geo/datetime.h"

namespace vegstream::flight {

// What a keyframe's altitude is measured from.
enum class AltRef {
  Terrain,  // metres above the ground under the keyframe (the default in JSON)
  Msl,      // metres above mean sea level (the dataset's height datum)
};

struct Keyframe {
  double t = 0.0;     // seconds of flight time
  double lat = 0.0;   // degrees, WGS 84
  double lon = 0.0;   // degrees, WGS 84
  double altM = 0.0;  // metres, measured from altRef
  AltRef altRef = AltRef::Terrain;
  double headingDeg = 0.0;  // 0 = north, clockwise (90 = east)
  double pitchDeg = 0.0;    // 0 = level, negative looks down, in [-90, 90]
};

struct ColliderKeyframe {
  double t = 0.0;
  double lat = 0.0;
  double lon = 0.0;
  double altM = 0.0;  // of the collider's centre (a capsule's middle)
  AltRef altRef = AltRef::Terrain;
};

struct Collider {
  enum class Shape { Sphere, Capsule };
  std::string name;
  Shape shape = Shape::Sphere;
  double radiusM = 1.0;
  double lengthM = 0.0;                     // capsule only: distance between the two end-cap centres (vertical)
  std::vector<ColliderKeyframe> keyframes;  // at least one; one keyframe = a static collider
};

// A local wind source that moves along its own keyframes (positioned like a collider's centre).
// Its own enum, so that flight/ stays independent of simulation/ (simulation::WindSourceType
// has the same three kinds).
struct WindSourceSpec {
  enum class Type { Fan, Whirlwind, Rotor };
  std::string name;
  Type type = Type::Fan;
  double radiusM = 1.0;                     // > 0: reach (fan: range; whirlwind, rotor: radius of the disc)
  double strengthMps = 0.0;                 // 0 … 100: the peak wind speed it adds
  std::optional<double> directionDeg;       // fan only (required there): where it blows TOWARDS, clockwise from north
  std::vector<ColliderKeyframe> keyframes;  // at least one; one keyframe = a fixed source
};

// The path's "wind" section: each value absent = the simulation's default (or the command
// line's, which wins over the path).
struct WindSection {
  std::optional<double> speedMps;      // mean wind, 0 … 100 m/s
  std::optional<double> directionDeg;  // where the wind comes FROM, clockwise from north; any finite value
  std::optional<double> gustiness;     // 0 … 1
  std::vector<WindSourceSpec> sources;
};

struct FlightPath {
  std::string name;
  std::string description;          // free text, optional
  std::vector<Keyframe> keyframes;  // at least two, t strictly increasing, first t = 0
  std::vector<Collider> colliders;
  std::optional<WindSection> wind;  // absent: no "wind" section
  // When the flight starts (issue 39: the sun's date-time at t = 0, advancing with t); absent: the
  // command line's --datetime, else the dataset's imagery time, else the default sun.
  std::optional<geo::DateTime> datetime;

  // Seconds: the last keyframe's t (the first is at 0).
  double duration() const;
  // The lon/lat box of the camera keyframes (not of the curve between them; not across the
  // antimeridian).
  geo::GeoBounds bounds() const;
};

// One problem found in a path: which field (e.g. "keyframes[3].lat", "colliders[0]") and what
// is wrong with it. The JSON reader adds the file name and line; others use validateFlightPath.
struct PathProblem {
  std::string field;
  std::string problem;
};

// The first violation of the rules above (counts, time order, finite numbers, lat/lon range,
// pitch range, non-negative terrain-relative altitudes, positive collider sizes, the wind
// section's ranges and its sources' sizes, directions and keyframes), if any.
std::optional<PathProblem> findProblem(const FlightPath& path);

// findProblem as a Status: "SOURCE: FIELD: PROBLEM", ErrorKind::InvalidInput.
Status validateFlightPath(const FlightPath& path, const std::string& sourceName);

// Whether the camera stays over the dataset: every keyframe and the interpolated curve between
// them (sampled) must lie inside datasetBounds. Error (InvalidInput): "path leaves the dataset
// at keyframes[i] (lat, lon) — dataset covers lat S … N, lon W … E".
Status checkInside(const FlightPath& path, const geo::GeoBounds& datasetBounds);

}  // namespace vegstream::flight
