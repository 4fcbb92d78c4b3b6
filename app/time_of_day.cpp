#include "app/time_of_day.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/wind_controls.h"

namespace vegstream::app {
namespace {

constexpr std::int64_t kMsPerDay = 86'400'000;
constexpr std::int64_t kMsPerMinute = 60'000;

std::int64_t localMs(const geo::DateTime& t) { return t.unixMs + std::int64_t{t.offsetMinutes} * kMsPerMinute; }

// Milliseconds since local midnight (floor, also before 1970).
std::int64_t msOfDay(const geo::DateTime& t) {
  const std::int64_t m = localMs(t) % kMsPerDay;
  return m < 0 ? m + kMsPerDay : m;
}

}  // namespace

geo::DateTime stepTime(const geo::DateTime& t, const TimeKeys& keys) {
  return geo::addSeconds(t, keys.steps * (keys.coarse ? kTimeCoarseStepS : kTimeStepS));
}

double localHours(const geo::DateTime& t) { return static_cast<double>(msOfDay(t)) / 3'600'000.0; }

geo::DateTime atLocalHours(const geo::DateTime& t, double hours) {
  const double clamped = std::clamp(std::isfinite(hours) ? hours : 0.0, 0.0, 24.0 - 1.0 / 60.0);
  const std::int64_t wanted = std::llround(clamped * 3'600'000.0);
  return {t.unixMs - msOfDay(t) + wanted, t.offsetMinutes};
}

std::string describeSun(const geo::DateTime& t, const geo::SolarPosition& sun) {
  std::string when = geo::formatIsoDateTime(t);  // 2024-06-21T10:00:00-07:32
  const std::size_t tee = when.find('T');
  std::string zone = when.size() >= 6 && when.back() != 'Z' ? when.substr(when.size() - 6) : "Z";
  when = when.substr(0, tee) + " " + when.substr(tee + 1, 5) + " " + zone;
  char buf[160];
  std::snprintf(buf, sizeof buf, "%s, sun %.0f° (%s), %.1f° %s", when.c_str(), sun.azimuthDeg,
                compassPoint(sun.azimuthDeg), std::fabs(sun.elevationDeg), sun.elevationDeg >= 0.0 ? "up" : "below");
  return buf;
}

}  // namespace vegstream::app
