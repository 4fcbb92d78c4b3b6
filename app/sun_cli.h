#pragma once
// The sun and exposure options that `fly`, `record` and `snapshot` share (issue 39):
// --datetime ISO-8601 (with a zone: 2015-08-18T17:58:00Z, 2026-06-21T06:45:00-06:00) and
// --exposure EV. One definition, so the commands spell and check them alike, and one rule for
// the date-time: the command line wins over the flight path's "datetime", which wins over the
// dataset's imagery time and the default sun (scene/sun_clock.h).

#include <optional>
#include <string>

#include "core/result.h"
#include "flight/flight_path.h"
#include "scene/scene.h"

namespace CLI {
class App;
}

namespace vegstream::app {

inline constexpr double kMinExposureEv = -10.0;
inline constexpr double kMaxExposureEv = 30.0;

// What the command line gave, as text (checked by checkSunOptions); absent: not given.
struct SunCli {
  std::optional<std::string> datetime;  // --datetime
  std::optional<std::string> exposure;  // --exposure
};

// The checked values.
struct SunSettings {
  std::optional<geo::DateTime> datetime;
  std::optional<float> exposureEv;
};

// Adds --datetime and --exposure to a subcommand.
void addSunOptions(CLI::App& cmd, SunCli& out);

// Parses and checks the given values: InvalidInput, one message naming the option and the
// problem ("--datetime \"2026-13-01\": month 13 does not exist (01–12)", "--exposure nan: must be
// a number of EV from -10 to 30").
Result<SunSettings> checkSunOptions(const SunCli& cli);

// Sets the scene's sun: --datetime, else the path's "datetime" (path may be null), else none
// (the scene then takes the dataset's imagery time or the default); --exposure.
void applySunOptions(const SunSettings& sun, const flight::FlightPath* path, scene::SceneOptions& so);

}  // namespace vegstream::app
