#pragma once
// Records an interactively flown path as a flight path (flight_path.h) that `vegstream record`
// replays: one keyframe every `intervalS` of flight time (and one at stop), altitudes MSL, so
// the replay flies exactly the recorded heights whatever the terrain resolution.

#include <filesystem>
#include <string>

#include "core/result.h"
#include "flight/flight_path.h"
#include "flight/path_sampler.h"

namespace vegstream::app {

class PathRecorder {
 public:
  explicit PathRecorder(double intervalS = 0.5) : intervalS_(intervalS) {}

  // Starts a new recording at wall/flight time `nowS` with the pose at that time.
  void start(double nowS, const flight::FlightSample& pose);
  bool recording() const { return recording_; }
  // Adds a keyframe if `intervalS` has passed since the last one.
  void add(double nowS, const flight::FlightSample& pose);
  // Ends the recording with a last keyframe at `nowS` (if later than the last one) and returns
  // the path; InvalidInput when it has fewer than two keyframes (nothing flown).
  Result<flight::FlightPath> stop(double nowS, const flight::FlightSample& pose, const std::string& name);

  std::size_t keyframeCount() const { return path_.keyframes.size(); }
  double elapsedS(double nowS) const { return recording_ ? nowS - startS_ : 0.0; }

 private:
  void append(double nowS, const flight::FlightSample& pose);

  double intervalS_;
  bool recording_ = false;
  double startS_ = 0.0;
  flight::FlightPath path_;
};

// Writes `path` as flight JSON (flightPathToJson) to `file`, atomically.
Status saveFlightPath(const flight::FlightPath& path, const std::filesystem::path& file);

}  // namespace vegstream::app
