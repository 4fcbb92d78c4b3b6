#include "flight/flight_path.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/number_text.h"
#include "flight/path_sampler.h"

namespace vegstream::flight {
namespace {

std::string num(double v, int decimals = 6) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

std::string at(const std::string& list, std::size_t i) { return list + "[" + std::to_string(i) + "]"; }

std::optional<PathProblem> checkNumber(const std::string& field, double v, double lo, double hi) {
  if (!std::isfinite(v)) return PathProblem{field, "is not a finite number"};
  if (v < lo || v > hi) return PathProblem{field, num(v) + " is out of range [" + num(lo, 0) + ", " + num(hi, 0) + "]"};
  return std::nullopt;
}

// Shared by camera and collider keyframes: time order and the position fields.
template <typename K>
std::optional<PathProblem> checkPositions(const std::string& list, const std::vector<K>& keys) {
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const K& k = keys[i];
    const std::string f = at(list, i);
    if (auto p = checkNumber(f + ".t", k.t, 0.0, 1e9)) return p;
    if (i > 0 && !(k.t > keys[i - 1].t))
      return PathProblem{f + ".t", "t = " + num(k.t, 3) + " s is not after " + at(list, i - 1) + ".t = " +
                                       num(keys[i - 1].t, 3) + " s (keyframes must be in increasing time order)"};
    if (auto p = checkNumber(f + ".lat", k.lat, -90.0, 90.0)) return p;
    if (auto p = checkNumber(f + ".lon", k.lon, -180.0, 180.0)) return p;
    if (auto p = checkNumber(f + ".alt_m", k.altM, -1e5, 1e5)) return p;
    if (k.altRef == AltRef::Terrain && k.altM < 0.0)
      return PathProblem{f + ".alt_m", num(k.altM, 1) + " m above the terrain is underground (use >= 0)"};
  }
  return std::nullopt;
}

// A wind value: finite, lo ≤ v ≤ hi ("must be ≥ 0 m/s, found -3").
std::optional<PathProblem> checkWindValue(const std::string& field, double v, double lo, double hi,
                                          const std::string& unit) {
  if (!std::isfinite(v)) return PathProblem{field, "is not a finite number"};
  if (v < lo) return PathProblem{field, "must be ≥ " + numberText(lo) + unit + ", found " + numberText(v)};
  if (v > hi) return PathProblem{field, "must be ≤ " + numberText(hi) + unit + ", found " + numberText(v)};
  return std::nullopt;
}

const char* typeName(WindSourceSpec::Type type) {
  switch (type) {
    case WindSourceSpec::Type::Fan: return "fan";
    case WindSourceSpec::Type::Whirlwind: return "whirlwind";
    case WindSourceSpec::Type::Rotor: return "rotor";
  }
  return "?";
}

std::optional<PathProblem> checkWind(const WindSection& wind) {
  constexpr double kMaxSpeedMps = 100.0;  // simulation::kMaxWindSpeedMps (flight/ does not depend on simulation/)
  if (wind.speedMps)
    if (auto p = checkWindValue("wind.speed_mps", *wind.speedMps, 0.0, kMaxSpeedMps, " m/s")) return p;
  if (wind.directionDeg && !std::isfinite(*wind.directionDeg))
    return PathProblem{"wind.direction_deg", "is not a finite number"};
  if (wind.gustiness)
    if (auto p = checkWindValue("wind.gustiness", *wind.gustiness, 0.0, 1.0, "")) return p;
  for (std::size_t i = 0; i < wind.sources.size(); ++i) {
    const WindSourceSpec& src = wind.sources[i];
    const std::string f = at("wind.sources", i);
    if (src.name.empty()) return PathProblem{f + ".name", "a wind source needs a name"};
    if (src.keyframes.empty()) return PathProblem{f + ".keyframes", "a wind source needs at least 1 keyframe"};
    if (!(src.radiusM > 0.0) || !std::isfinite(src.radiusM))
      return PathProblem{f + ".radius_m", "must be a positive number of metres"};
    if (auto p = checkWindValue(f + ".strength_mps", src.strengthMps, 0.0, kMaxSpeedMps, " m/s")) return p;
    if (src.type == WindSourceSpec::Type::Fan && !src.directionDeg)
      return PathProblem{f + ".direction_deg",
                         "a fan needs direction_deg (where it blows towards, degrees clockwise from north)"};
    if (src.type != WindSourceSpec::Type::Fan && src.directionDeg)
      return PathProblem{f + ".direction_deg",
                         std::string("only a fan has a direction (a ") + typeName(src.type) + " blows all around)"};
    if (src.directionDeg && !std::isfinite(*src.directionDeg))
      return PathProblem{f + ".direction_deg", "is not a finite number"};
    if (auto p = checkPositions(f + ".keyframes", src.keyframes)) return p;
  }
  return std::nullopt;
}

bool lonInside(double lon, const geo::GeoBounds& b) {
  if (!b.crossesAntimeridian()) return lon >= b.westDeg && lon <= b.eastDeg;
  return lon >= b.westDeg || lon <= b.eastDeg;
}

bool inside(double lat, double lon, const geo::GeoBounds& b) {
  return lat >= b.southDeg && lat <= b.northDeg && lonInside(lon, b);
}

std::string covers(const geo::GeoBounds& b) {
  return "dataset covers lat " + num(b.southDeg) + " … " + num(b.northDeg) + ", lon " + num(b.westDeg) + " … " +
         num(b.eastDeg);
}

}  // namespace

double FlightPath::duration() const { return keyframes.empty() ? 0.0 : keyframes.back().t; }

geo::GeoBounds FlightPath::bounds() const {
  if (keyframes.empty()) return {};
  geo::GeoBounds b{keyframes[0].lon, keyframes[0].lat, keyframes[0].lon, keyframes[0].lat};
  for (const Keyframe& k : keyframes) {
    b.westDeg = std::min(b.westDeg, k.lon);
    b.eastDeg = std::max(b.eastDeg, k.lon);
    b.southDeg = std::min(b.southDeg, k.lat);
    b.northDeg = std::max(b.northDeg, k.lat);
  }
  return b;
}

std::optional<PathProblem> findProblem(const FlightPath& path) {
  if (path.keyframes.size() < 2)
    return PathProblem{"keyframes",
                       "a path needs at least 2 keyframes, found " + std::to_string(path.keyframes.size())};
  if (path.keyframes[0].t != 0.0)
    return PathProblem{"keyframes[0].t", "the first keyframe must be at t = 0, found " + num(path.keyframes[0].t, 3)};
  if (auto p = checkPositions("keyframes", path.keyframes)) return p;
  for (std::size_t i = 0; i < path.keyframes.size(); ++i) {
    const Keyframe& k = path.keyframes[i];
    if (auto p = checkNumber(at("keyframes", i) + ".heading", k.headingDeg, -1e6, 1e6)) return p;
    if (auto p = checkNumber(at("keyframes", i) + ".pitch", k.pitchDeg, -90.0, 90.0)) return p;
  }
  for (std::size_t c = 0; c < path.colliders.size(); ++c) {
    const Collider& col = path.colliders[c];
    const std::string f = at("colliders", c);
    if (col.keyframes.empty()) return PathProblem{f + ".keyframes", "a collider needs at least 1 keyframe"};
    if (!(col.radiusM > 0.0) || !std::isfinite(col.radiusM))
      return PathProblem{f + ".radius_m", "must be a positive number of metres"};
    if (col.shape == Collider::Shape::Capsule && (!(col.lengthM > 0.0) || !std::isfinite(col.lengthM)))
      return PathProblem{f + ".length_m", "a capsule needs a positive length_m"};
    if (auto p = checkPositions(f + ".keyframes", col.keyframes)) return p;
  }
  if (path.wind)
    if (auto p = checkWind(*path.wind)) return p;
  return std::nullopt;
}

Status validateFlightPath(const FlightPath& path, const std::string& sourceName) {
  if (auto p = findProblem(path))
    return makeError(ErrorKind::InvalidInput, sourceName + ": " + p->field + ": " + p->problem);
  return {};
}

Status checkInside(const FlightPath& path, const geo::GeoBounds& datasetBounds) {
  for (std::size_t i = 0; i < path.keyframes.size(); ++i) {
    const Keyframe& k = path.keyframes[i];
    if (!inside(k.lat, k.lon, datasetBounds))
      return makeError(ErrorKind::InvalidInput, "path leaves the dataset at keyframes[" + std::to_string(i) + "] (" +
                                                    num(k.lat) + ", " + num(k.lon) + ") — " + covers(datasetBounds));
  }
  if (findProblem(path)) return {};  // the curve is undefined; the validator reports why
  // The spline may bulge past the keyframes' box at a turn near the edge: sample it.
  const PathSampler sampler(path);
  for (std::size_t i = 0; i + 1 < path.keyframes.size(); ++i) {
    constexpr int kSteps = 32;
    for (int j = 1; j < kSteps; ++j) {
      const double t = path.keyframes[i].t + (path.keyframes[i + 1].t - path.keyframes[i].t) * j / kSteps;
      const geo::Geodetic g = sampler.horizontal(t);
      if (!inside(g.latDeg, g.lonDeg, datasetBounds))
        return makeError(ErrorKind::InvalidInput, "path leaves the dataset between keyframes[" + std::to_string(i) +
                                                      "] and [" + std::to_string(i + 1) + "] at t = " + num(t, 2) +
                                                      " s (" + num(g.latDeg) + ", " + num(g.lonDeg) + ") — " +
                                                      covers(datasetBounds));
    }
  }
  return {};
}

}  // namespace vegstream::flight
