#pragma once
// Helpers shared by the geo tests: an independent metric (GeographicLib's geodesic) to express
// round-trip errors in metres.

#include <cmath>

#include <GeographicLib/Geodesic.hpp>

#include "geo/geodetic.h"

namespace vegstream::geo::test {

// 3-D distance between two geodetic positions: geodesic on the ellipsoid, plus height.
inline double metresBetween(const Geodetic& a, const Geodetic& b) {
  double s12 = 0.0;
  GeographicLib::Geodesic::WGS84().Inverse(a.latDeg, a.lonDeg, b.latDeg, b.lonDeg, s12);
  return std::hypot(s12, a.heightM - b.heightM);
}

// The point `distanceM` from `from` along the geodesic leaving at `azimuthDeg`, at `heightM`.
inline Geodetic travel(const Geodetic& from, double azimuthDeg, double distanceM, double heightM) {
  Geodetic to;
  to.heightM = heightM;
  GeographicLib::Geodesic::WGS84().Direct(from.latDeg, from.lonDeg, azimuthDeg, distanceM, to.latDeg, to.lonDeg);
  return to;
}

}  // namespace vegstream::geo::test
