#pragma once
// The sun's apparent position seen from a point on the earth at an instant: NOAA's solar
// calculator (see solar_position.cpp for the source), with NOAA's atmospheric refraction. Good
// to about 0.01° against NREL's SPA for years 1800–2100 (NOAA quotes ±0.5 min for sunrise and
// sunset within ±72° latitude); the observer's height and the weather are not inputs.

#include <cstdint>

#include <glm/vec3.hpp>

namespace vegstream::geo {

struct SolarPosition {
  double azimuthDeg = 0.0;         // [0, 360), clockwise from true north (90 = east)
  double elevationDeg = 0.0;       // above the horizon, refraction included (negative: below)
  double zenithDeg = 90.0;         // 90 − elevationDeg (refraction included)
  double declinationDeg = 0.0;     // the sun's apparent declination
  double equationOfTimeMin = 0.0;  // apparent minus mean solar time, minutes
};

// At `unixMs` (UTC milliseconds since 1970, as DateTime::unixMs) seen from latitude `latDeg`
// (−90 … 90, north positive) and longitude `lonDeg` (east positive; any value, ±180 alike).
SolarPosition solarPosition(std::int64_t unixMs, double latDeg, double lonDeg);

// NOAA's refraction correction (degrees, ≥ 0) added to a geometric (airless) elevation:
// Saemundsson-like piecewise fits, 0 above 85°, about 0.48° at the horizon.
double noaaRefractionDeg(double geometricElevationDeg);

// The unit vector towards the sun in the local East-North-Up frame (x east, y north, z up).
glm::dvec3 sunDirectionEnu(const SolarPosition& p);

}  // namespace vegstream::geo
