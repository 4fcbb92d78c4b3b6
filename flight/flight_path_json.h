#pragma once
// Flight paths as JSON files (the format is documented in flight/README.md). Reading is
// strict: every problem is one InvalidInput error naming the file, the line and column, and
// the field path ("paths/x.json:14:7: keyframes[3].lat: 95.000000 is out of range [-90, 90]");
// unknown keys are refused (with a suggestion when one is close), so typos never pass silently.

#include <filesystem>
#include <string>
#include <string_view>

#include "core/result.h"
#include "flight/flight_path.h"

namespace vegstream::flight {

// Parses and validates (findProblem) a flight path. sourceName is used in messages and, when
// the JSON has no "name", as the path's name (its stem: "paths/orbit.json" → "orbit").
Result<FlightPath> parseFlightPath(std::string_view text, const std::string& sourceName);

// Reads a file and parses it; a missing file is ErrorKind::NotFound, unreadable ErrorKind::Io.
Result<FlightPath> loadFlightPath(const std::filesystem::path& file);

// The JSON text of a path, one keyframe per line, that parseFlightPath reads back to the same
// path (lat/lon to 1e-7°, metres and degrees to 1e-3).
std::string flightPathToJson(const FlightPath& path);

}  // namespace vegstream::flight
