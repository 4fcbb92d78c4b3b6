// The window's wind keys (wind_controls.h): stepping, clamping and the HUD's wind line.

#include "app/wind_controls.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace vegstream::app {

namespace {
// Into [0, 360); fmod keeps the sign of its argument, and −0.0 / 360.0 (rounding) fold to 0.
double wrapDegrees(double deg) {
  double d = std::fmod(deg, 360.0);
  if (d < 0.0) d += 360.0;
  return d >= 360.0 || d == 0.0 ? 0.0 : d;
}
}  // namespace

simulation::WindOptions clampWind(const simulation::WindOptions& wind) {
  simulation::WindOptions w = wind;
  w.speedMps = std::clamp(std::isfinite(w.speedMps) ? w.speedMps : 0.0, 0.0, simulation::kMaxWindSpeedMps);
  w.gustiness = std::clamp(std::isfinite(w.gustiness) ? w.gustiness : 0.0, 0.0, 1.0);
  w.directionDeg = std::isfinite(w.directionDeg) ? w.directionDeg : 0.0;
  return w;
}

simulation::WindOptions stepWind(const simulation::WindOptions& wind, const WindKeys& keys) {
  simulation::WindOptions w = clampWind(wind);
  const double speedStep = keys.coarse ? kWindSpeedCoarseStepMps : kWindSpeedStepMps;
  w.speedMps += keys.speedSteps * speedStep;
  if (keys.directionSteps != 0)
    w.directionDeg = wrapDegrees(w.directionDeg + keys.directionSteps * kWindDirectionStepDeg);
  if (keys.gustinessSteps != 0)
    w.gustiness = std::round((w.gustiness + keys.gustinessSteps * kGustinessStep) * 100.0) / 100.0;
  return clampWind(w);
}

const char* compassPoint(double directionDeg) {
  static const char* kPoints[] = {"N", "NE", "E", "SE", "S", "SW", "W", "NW"};
  const double d = wrapDegrees(std::isfinite(directionDeg) ? directionDeg : 0.0);
  return kPoints[static_cast<int>(std::floor((d + 22.5) / 45.0)) % 8];
}

std::string describeWind(const simulation::WindOptions& wind) {
  char buf[96];
  std::snprintf(buf, sizeof(buf), "%.1f m/s from %.0f\xC2\xB0 (%s), gusts %.2f", wind.speedMps,
                wrapDegrees(wind.directionDeg), compassPoint(wind.directionDeg), wind.gustiness);
  return buf;
}

}  // namespace vegstream::app
