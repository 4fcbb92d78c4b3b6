#pragma once
// The sun over a scene (issue 39): the date and time a flight starts at, and the sun's position
// at any flight time t — solarPosition(start + t) at the dataset's centre. The start comes from,
// in this order: the command line or the flight path (SceneOptions::datetime); the dataset's
// imagery acquisition time (dataset.json "imagery.datetime"); else a fixed mid-morning summer sun,
// 10:00 local mean solar time on 21 June 2024 at the centre's longitude (app/README.md).

#include <optional>
#include <string>

#include "core/result.h"
#include "geo/datetime.h"
#include "geo/solar_position.h"

namespace vegstream::scene {

enum class DatetimeSource {
  Option,   // --datetime or the flight path's "datetime"
  Dataset,  // dataset.json's imagery.datetime
  Default,  // the fixed mid-morning summer sun
};

// "option", "dataset", "default" (recording.json's datetime_source).
const char* toString(DatetimeSource source);

// 10:00 local mean solar time on 21 June 2024 at `lonDeg`, written in that mean-solar offset
// (lon/15 h, to the minute): UTC = 10:00 − lon/15 h. Zion (113.05° W): 2024-06-21T10:00:00-07:32.
geo::DateTime defaultDatetime(double lonDeg);

struct SunClock {
  geo::DateTime start;  // the date-time at flight time 0
  DatetimeSource source = DatetimeSource::Default;
  double latDeg = 0.0, lonDeg = 0.0;  // where the sun is seen from: the dataset's centre

  geo::DateTime at(double timeS) const { return geo::addSeconds(start, timeS); }
  geo::SolarPosition sunAt(double timeS) const { return geo::solarPosition(at(timeS).unixMs, latDeg, lonDeg); }
};

// The clock for a dataset centred at (latDeg, lonDeg): `option` when given, else
// `imageryDatetime` (dataset.json's text; empty: none), else defaultDatetime. A malformed
// imageryDatetime is an InvalidInput error "'DATASET_JSON': field 'imagery.datetime' …" naming
// `datasetJsonName` (the file or URL, as the dataset reader names it).
Result<SunClock> resolveSunClock(const std::optional<geo::DateTime>& option, const std::string& imageryDatetime,
                                 const std::string& datasetJsonName, double latDeg, double lonDeg);

}  // namespace vegstream::scene
