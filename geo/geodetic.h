#pragma once
// Geodetic positions (WGS 84 latitude/longitude in degrees, ellipsoidal height in metres).

namespace vegstream::geo {

struct Geodetic {
  double latDeg = 0.0;
  double lonDeg = 0.0;
  double heightM = 0.0;
};

}  // namespace vegstream::geo
