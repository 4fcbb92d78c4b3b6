#include "geo/solar_position.h"

#include <cmath>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "geo/datetime.h"

namespace vegstream::geo {
namespace {

constexpr double kPi = 3.14159265358979323846;
double rad(double d) { return d * kPi / 180.0; }
double deg(double r) { return r * 180.0 / kPi; }

std::int64_t msOf(std::string_view iso) {
  const Result<DateTime> t = parseIsoDateTime(iso);
  EXPECT_TRUE(t.ok()) << iso;
  return t.ok() ? t->unixMs : 0;
}

// Smallest angle between two azimuths, degrees.
double azimuthGap(double a, double b) {
  const double d = std::fmod(std::fabs(a - b), 360.0);
  return std::min(d, 360.0 - d);
}

// The airless elevation from the declination and equation of time the function reports,
// through the textbook hour angle: an independent check of the sheet's columns AB–AE.
double geometricElevation(std::int64_t unixMs, double latDeg, double lonDeg, const SolarPosition& p) {
  const double utcMin = std::fmod(double(unixMs) / 60000.0, 1440.0);
  const double ha = rad((utcMin + p.equationOfTimeMin + 4.0 * lonDeg) / 4.0 - 180.0);
  const double lat = rad(latDeg), dec = rad(p.declinationDeg);
  return deg(std::asin(std::sin(lat) * std::sin(dec) + std::cos(lat) * std::cos(dec) * std::cos(ha)));
}

TEST(SolarPosition, NrelSpaExample) {
  // Reda & Andreas (2004), NREL/TP-560-34302, table A5.1: 2003-10-17 12:30:30 at −7 h, Golden
  // CO. SPA: topocentric zenith 50.11162°, azimuth 194.34024° (at 820 mbar, 11 °C, 1830 m —
  // NOAA's standard refraction and no parallax account for a few thousandths of a degree),
  // geocentric declination −9.31434°, equation of time 14.641503 min.
  const SolarPosition p = solarPosition(msOf("2003-10-17T12:30:30-07:00"), 39.742476, -105.1786);
  EXPECT_NEAR(p.zenithDeg, 50.11162, 0.1);
  EXPECT_NEAR(p.azimuthDeg, 194.34024, 0.1);
  EXPECT_NEAR(p.zenithDeg, 50.11162, 0.01);  // what NOAA's sheet actually achieves here
  EXPECT_NEAR(p.azimuthDeg, 194.34024, 0.01);
  EXPECT_NEAR(p.declinationDeg, -9.31434, 0.005);
  EXPECT_NEAR(p.equationOfTimeMin, 14.641503, 0.01);
  EXPECT_DOUBLE_EQ(p.zenithDeg, 90.0 - p.elevationDeg);
}

TEST(SolarPosition, NoaaSpreadsheetRows) {
  // NOAA_Solar_Calculations_day.xls, its default row 2 (6/21/2010 0:06 at −6 h, JD 2455368.754167)
  // and a row on 9/21/2023 13:33 UTC (JD 2460209.064583): the sheet's apparent longitude P and
  // corrected obliquity R (89.7854391814863°, 23.4384863293544°; 178.316980310654°,
  // 23.4385024897594°, as tabulated by pysunNOAA's tests) give its declination T = asin(sin R ·
  // sin P): 23.4383121595° and 0.6693644906°.
  EXPECT_NEAR(solarPosition(msOf("2010-06-21T00:06:00-06:00"), 40.0, -105.0).declinationDeg, 23.4383121595, 1e-6);
  EXPECT_NEAR(solarPosition(msOf("2023-09-21T13:33:00Z"), 40.0, -105.0).declinationDeg, 0.6693644906, 1e-6);
}

TEST(SolarPosition, MeeusExamples) {
  // Meeus, Astronomical Algorithms, ex. 25.a (1992-10-13 0h TD, low accuracy): δ = −7.78507°;
  // ex. 28.b (eq. 28.3, the sheet's equation of time): E = 13m 42.7s. ΔT (59 s) is ignored.
  const SolarPosition p = solarPosition(msOf("1992-10-13T00:00:00Z"), 0.0, 0.0);
  EXPECT_NEAR(p.declinationDeg, -7.78507, 0.001);
  EXPECT_NEAR(p.equationOfTimeMin, 13.0 + 42.7 / 60.0, 0.005);
}

TEST(SolarPosition, NoonIsDueSouthAtTheEquationOfTime) {
  // Zion (37.3° N, 113.05° W) on the June solstice: local apparent noon is 12:00 UTC − lon/15 h
  // − E. Then the sun is due south at 90 − φ + δ (+ refraction).
  const double lat = 37.3, lon = -113.05;
  const std::int64_t midnight = msOf("2024-06-21T00:00:00Z");
  const double eot = solarPosition(midnight + 19 * 3'600'000, lat, lon).equationOfTimeMin;
  const std::int64_t noon = midnight + std::llround((720.0 - 4.0 * lon - eot) * 60'000.0);
  const SolarPosition p = solarPosition(noon, lat, lon);
  EXPECT_NEAR(p.azimuthDeg, 180.0, 0.01);
  const double geometric = 90.0 - lat + p.declinationDeg;
  EXPECT_NEAR(p.elevationDeg, geometric + noaaRefractionDeg(geometric), 0.001);
  EXPECT_NEAR(p.elevationDeg, 76.15, 0.05);
  // The morning sun is in the east and lower, the afternoon sun in the west.
  EXPECT_LT(solarPosition(noon - 3 * 3'600'000, lat, lon).azimuthDeg, 180.0);
  EXPECT_GT(solarPosition(noon - 3 * 3'600'000, lat, lon).azimuthDeg, 60.0);
  EXPECT_GT(solarPosition(noon + 3 * 3'600'000, lat, lon).azimuthDeg, 180.0);
}

TEST(SolarPosition, PolarDayAndNight) {
  // 80° N at local midnight on the June solstice: the sun is due north, 80 + 23.44 − 90 up.
  const SolarPosition day = solarPosition(msOf("2024-06-21T00:00:00Z"), 80.0, 0.0);
  EXPECT_NEAR(day.elevationDeg, 13.44 + noaaRefractionDeg(13.44), 0.05);
  EXPECT_LT(azimuthGap(day.azimuthDeg, 0.0), 1.0);
  // The same place at noon on the December solstice: due south, 13.44° below the horizon.
  const SolarPosition night = solarPosition(msOf("2024-12-21T12:00:00Z"), 80.0, 0.0);
  EXPECT_NEAR(night.elevationDeg, -13.44, 0.05);
  EXPECT_LT(azimuthGap(night.azimuthDeg, 180.0), 1.0);
  // Antarctica mirrors it: 80° S at its midnight in December sees the sun due south.
  const SolarPosition south = solarPosition(msOf("2024-12-21T00:00:00Z"), -80.0, 0.0);
  EXPECT_NEAR(south.elevationDeg, 13.44 + noaaRefractionDeg(13.44), 0.05);
  EXPECT_LT(azimuthGap(south.azimuthDeg, 180.0), 1.0);
}

TEST(SolarPosition, AtThePoleTheElevationIsTheDeclinationAllDay) {
  for (int hour = 0; hour < 24; hour += 5) {
    const SolarPosition p = solarPosition(msOf("2024-06-21T00:00:00Z") + hour * 3'600'000, 90.0, 0.0);
    EXPECT_NEAR(p.elevationDeg, p.declinationDeg + noaaRefractionDeg(p.declinationDeg), 1e-9);
    EXPECT_TRUE(std::isfinite(p.azimuthDeg));
    EXPECT_GE(p.azimuthDeg, 0.0);
    EXPECT_LT(p.azimuthDeg, 360.0);
  }
}

TEST(SolarPosition, TheDateLineChangesTheDateNotTheSun) {
  // Noon on the 21st just west of the date line is noon on the 20th just east of it: the same
  // instant, and so nearly the same sun (Fiji, 17.7° S, in June: high in the north).
  const std::int64_t west = msOf("2024-06-21T12:00:00+12:00");
  const std::int64_t east = msOf("2024-06-20T12:00:00-12:00");
  ASSERT_EQ(west, east);
  const SolarPosition a = solarPosition(west, -17.7, 179.999);
  const SolarPosition b = solarPosition(east, -17.7, -179.999);
  EXPECT_NEAR(a.elevationDeg, b.elevationDeg, 0.01);
  EXPECT_LT(azimuthGap(a.azimuthDeg, b.azimuthDeg), 0.01);
  EXPECT_NEAR(a.elevationDeg, 90.0 - 17.7 - 23.44, 0.5);
  EXPECT_LT(azimuthGap(a.azimuthDeg, 0.0), 1.0);
  const SolarPosition c = solarPosition(west, -17.7, 180.0), d = solarPosition(west, -17.7, -180.0);
  EXPECT_NEAR(c.elevationDeg, d.elevationDeg, 1e-9);
  EXPECT_LT(azimuthGap(c.azimuthDeg, d.azimuthDeg), 1e-9);
}

TEST(SolarPosition, RefractionFollowsNoaasFit) {
  EXPECT_NEAR(noaaRefractionDeg(0.0), 1735.0 / 3600.0, 1e-12);  // 0.48° at the horizon
  EXPECT_EQ(noaaRefractionDeg(85.5), 0.0);
  EXPECT_EQ(noaaRefractionDeg(90.0), 0.0);
  EXPECT_NEAR(noaaRefractionDeg(45.0), (58.1 - 0.07 + 0.000086) / 3600.0, 1e-12);  // tan 45° = 1
  // The pieces meet: no step at 5° or at −0.575° larger than 0.002°.
  EXPECT_NEAR(noaaRefractionDeg(5.0 - 1e-9), noaaRefractionDeg(5.0 + 1e-9), 0.002);
  EXPECT_NEAR(noaaRefractionDeg(-0.575 - 1e-9), noaaRefractionDeg(-0.575 + 1e-9), 0.002);
  // It grows towards the horizon.
  double previous = 0.0;
  for (double e = 80.0; e >= -0.5; e -= 0.5) {
    const double r = noaaRefractionDeg(e);
    EXPECT_GT(r, previous) << e;
    previous = r;
  }
}

TEST(SolarPosition, RefractionLiftsTheSunAtSunrise) {
  // Find the instant the apparent sun touches the horizon on a Zion morning (bisection on the
  // refracted elevation), then check the airless sun is still about half a degree below it.
  const double lat = 37.3, lon = -113.05;
  std::int64_t lo = msOf("2024-06-21T11:00:00Z"), hi = msOf("2024-06-21T13:00:00Z");
  ASSERT_LT(solarPosition(lo, lat, lon).elevationDeg, 0.0);
  ASSERT_GT(solarPosition(hi, lat, lon).elevationDeg, 0.0);
  while (hi - lo > 100) {
    const std::int64_t mid = lo + (hi - lo) / 2;
    (solarPosition(mid, lat, lon).elevationDeg < 0.0 ? lo : hi) = mid;
  }
  const SolarPosition p = solarPosition(hi, lat, lon);
  EXPECT_NEAR(p.elevationDeg, 0.0, 0.005);
  const double airless = geometricElevation(hi, lat, lon, p);
  EXPECT_NEAR(p.elevationDeg - airless, noaaRefractionDeg(airless), 1e-6);
  EXPECT_GT(airless, -0.62);
  EXPECT_LT(airless, -0.50);
  EXPECT_GT(p.azimuthDeg, 55.0);  // north of east in June
  EXPECT_LT(p.azimuthDeg, 65.0);
}

TEST(SolarPosition, SunDirectionIsAUnitVectorInEastNorthUp) {
  const auto dir = [](double az, double el) {
    SolarPosition p;
    p.azimuthDeg = az;
    p.elevationDeg = el;
    return sunDirectionEnu(p);
  };
  const glm::dvec3 east = dir(90.0, 0.0), south = dir(180.0, 30.0), up = dir(0.0, 90.0);
  EXPECT_NEAR(east.x, 1.0, 1e-12);
  EXPECT_NEAR(east.y, 0.0, 1e-12);
  EXPECT_NEAR(east.z, 0.0, 1e-12);
  EXPECT_NEAR(south.x, 0.0, 1e-12);
  EXPECT_NEAR(south.y, -std::cos(rad(30.0)), 1e-12);
  EXPECT_NEAR(south.z, 0.5, 1e-12);
  EXPECT_NEAR(up.z, 1.0, 1e-12);
  const SolarPosition p = solarPosition(msOf("2003-10-17T12:30:30-07:00"), 39.742476, -105.1786);
  const glm::dvec3 d = sunDirectionEnu(p);
  EXPECT_NEAR(glm::length(d), 1.0, 1e-12);
  EXPECT_NEAR(deg(std::asin(d.z)), p.elevationDeg, 1e-9);
  EXPECT_NEAR(std::fmod(deg(std::atan2(d.x, d.y)) + 360.0, 360.0), p.azimuthDeg, 1e-9);
}

}  // namespace
}  // namespace vegstream::geo
