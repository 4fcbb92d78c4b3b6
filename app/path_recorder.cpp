#include "app/path_recorder.h"

#include <algorithm>
#include <fstream>

#include "core/atomic_file.h"
#include "flight/flight_path_json.h"

namespace vegstream::app {
namespace {
// Keyframe times are written to 1e-3 s (flightPathToJson): keep them that far apart.
constexpr double kMinStepS = 0.01;
}  // namespace

void PathRecorder::start(double nowS, const flight::FlightSample& pose) {
  path_ = {};
  recording_ = true;
  startS_ = nowS;
  append(nowS, pose);
}

void PathRecorder::append(double nowS, const flight::FlightSample& pose) {
  flight::Keyframe k;
  k.t = nowS - startS_;
  k.lat = pose.position.latDeg;
  k.lon = pose.position.lonDeg;
  k.altM = pose.position.heightM;
  k.altRef = flight::AltRef::Msl;
  k.headingDeg = pose.headingDeg;
  k.pitchDeg = std::clamp(pose.pitchDeg, -90.0, 90.0);
  path_.keyframes.push_back(k);
}

void PathRecorder::add(double nowS, const flight::FlightSample& pose) {
  if (!recording_ || path_.keyframes.empty()) return;
  if (nowS - startS_ - path_.keyframes.back().t >= intervalS_) append(nowS, pose);
}

Result<flight::FlightPath> PathRecorder::stop(double nowS, const flight::FlightSample& pose, const std::string& name) {
  if (!recording_) return makeError(ErrorKind::InvalidInput, "no path is being recorded");
  recording_ = false;
  if (!path_.keyframes.empty() && nowS - startS_ - path_.keyframes.back().t >= kMinStepS) append(nowS, pose);
  if (path_.keyframes.size() < 2)
    return makeError(ErrorKind::InvalidInput, "the recording is too short: a flight path needs two keyframes");
  path_.name = name;
  path_.description = "flown interactively with `vegstream fly`; altitudes above mean sea level";
  if (auto s = flight::validateFlightPath(path_, name); !s) return s.error();
  return path_;
}

Status saveFlightPath(const flight::FlightPath& path, const std::filesystem::path& file) {
  const std::string text = flight::flightPathToJson(path);
  return writeTextAtomically(file, text);
}

}  // namespace vegstream::app
