// The sun over a scene (sun_clock.h).

#include "scene/sun_clock.h"

#include <cmath>

namespace vegstream::scene {
namespace {

// 2024-06-21T10:00:00Z: date -u -d 2024-06-21T10:00:00Z +%s → 1718964000.
constexpr std::int64_t kDefaultDayTenUtcMs = 1'718'964'000'000;

}  // namespace

const char* toString(DatetimeSource source) {
  switch (source) {
    case DatetimeSource::Option: return "option";
    case DatetimeSource::Dataset: return "dataset";
    case DatetimeSource::Default: return "default";
  }
  return "default";
}

geo::DateTime defaultDatetime(double lonDeg) {
  // Mean solar time runs 4 minutes ahead of UTC per degree east; to the minute, so that the
  // date-time reads back as 10:00 in its own offset.
  const int offsetMinutes = static_cast<int>(std::lround(lonDeg * 4.0));
  return {kDefaultDayTenUtcMs - std::int64_t{offsetMinutes} * 60'000, offsetMinutes};
}

Result<SunClock> resolveSunClock(const std::optional<geo::DateTime>& option, const std::string& imageryDatetime,
                                 const std::string& datasetJsonName, double latDeg, double lonDeg) {
  SunClock clock;
  clock.latDeg = latDeg;
  clock.lonDeg = lonDeg;
  if (option) {
    clock.start = *option;
    clock.source = DatetimeSource::Option;
  } else if (!imageryDatetime.empty()) {
    auto parsed = geo::parseIsoDateTime(imageryDatetime);
    if (!parsed)
      return makeError(ErrorKind::InvalidInput,
                       "'" + datasetJsonName + "': field 'imagery.datetime' " + parsed.error().message);
    clock.start = *parsed;
    clock.source = DatetimeSource::Dataset;
  } else {
    clock.start = defaultDatetime(lonDeg);
  }
  return clock;
}

}  // namespace vegstream::scene
