#include "app/sun_cli.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>

#include <CLI/CLI.hpp>

#include "core/number_text.h"

namespace vegstream::app {

void addSunOptions(CLI::App& cmd, SunCli& out) {
  cmd.add_option("--datetime", out.datetime,
                 "When the flight starts (the sun's position; the flight's clock advances it), ISO 8601 with a zone, "
                 "e.g. 2015-08-18T17:58:00Z or 2026-06-21T06:45:00-06:00 (default: the flight path's datetime, else "
                 "the imagery's acquisition time, else 10:00 local mean solar time on 21 June 2024)")
      ->type_name("ISO-8601");
  cmd.add_option("--exposure", out.exposure,
                 "Fixed exposure, EV100, " + numberText(kMinExposureEv) + " … " + numberText(kMaxExposureEv) +
                     " (default: automatic from each frame)")
      ->type_name("EV");
}

Result<SunSettings> checkSunOptions(const SunCli& cli) {
  SunSettings out;
  if (cli.datetime) {
    auto t = geo::parseIsoDateTime(*cli.datetime);
    if (!t) return makeError(ErrorKind::InvalidInput, "--datetime " + t.error().message);
    out.datetime = *t;
  }
  if (cli.exposure) {
    const std::string& text = *cli.exposure;
    const std::string problem =
        ": must be a number of EV from " + numberText(kMinExposureEv) + " to " + numberText(kMaxExposureEv);
    // strtod reads "nan" and "inf" too: the range check below refuses them.
    errno = 0;
    char* end = nullptr;
    const double v = text.empty() ? std::nan("") : std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE)
      return makeError(ErrorKind::InvalidInput, "--exposure \"" + text + "\"" + problem);
    if (!(v >= kMinExposureEv && v <= kMaxExposureEv))
      return makeError(ErrorKind::InvalidInput, "--exposure " + text + problem);
    out.exposureEv = static_cast<float>(v);
  }
  return out;
}

void applySunOptions(const SunSettings& sun, const flight::FlightPath* path, scene::SceneOptions& so) {
  so.datetime = sun.datetime;
  if (!so.datetime && path != nullptr) so.datetime = path->datetime;
  so.exposureEv = sun.exposureEv;
}

}  // namespace vegstream::app
