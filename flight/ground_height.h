#pragma once
// The one thing flights need from the terrain: its height at a lat/lon. A plain function so
// that flight/ stays testable without a dataset (tests pass lambdas; the app passes a lookup
// into the streamed height tiles).

#include <functional>

namespace vegstream::flight {

// Height of the ground (m MSL) at a lat/lon, NaN where unknown (callers treat NaN as 0).
using GroundHeight = std::function<double(double latDeg, double lonDeg)>;

}  // namespace vegstream::flight
