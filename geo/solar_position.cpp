// NOAA's solar position algorithm: the equations of the NOAA Global Monitoring Laboratory's
// Solar Calculator and its spreadsheets (NOAA_Solar_Calculations_day.xls,
// https://gml.noaa.gov/grad/solcalc/calcdetails.html), which follow Jean Meeus, "Astronomical
// Algorithms" (2nd ed., 1998), ch. 25 (the sun's low-accuracy position), ch. 22 (obliquity)
// and ch. 28 (equation of time, eq. 28.3), with the spreadsheet's atmospheric refraction
// correction (column AF, "Approx Atmospheric Refraction"). Column names in comments are the
// spreadsheet's. One change of form, not of value: the azimuth is atan2 of the hour angle
// instead of the sheet's acos, which divides by cos(latitude)·sin(zenith) and so fails at the
// poles and with the sun overhead.
#include "geo/solar_position.h"

#include <algorithm>
#include <cmath>

namespace vegstream::geo {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kJulianDayOfUnixEpoch = 2440587.5;
constexpr double kJ2000 = 2451545.0;
constexpr double kMsPerDay = 86'400'000.0;

double rad(double deg) { return deg * (kPi / 180.0); }
double deg(double rad) { return rad * (180.0 / kPi); }
double wrap(double v, double period) {
  const double r = std::fmod(v, period);
  const double w = r < 0.0 ? r + period : r;
  return w >= period ? 0.0 : w;  // −1e-17 + 360 rounds to 360
}

struct SunCoordinates {
  double declinationDeg = 0.0;
  double equationOfTimeMin = 0.0;
};

// Declination and equation of time at Julian century `jc` since J2000 (UT, ΔT ignored as in
// the spreadsheet).
SunCoordinates sunCoordinates(double jc) {
  const double l0 = wrap(280.46646 + jc * (36000.76983 + jc * 0.0003032), 360.0);     // I: geom mean long
  const double m = 357.52911 + jc * (35999.05029 - 0.0001537 * jc);                   // J: geom mean anom
  const double e = 0.016708634 - jc * (0.000042037 + 0.0000001267 * jc);              // K: eccentricity
  const double c = std::sin(rad(m)) * (1.914602 - jc * (0.004817 + 0.000014 * jc)) +  // L: eq of centre
                   std::sin(rad(2 * m)) * (0.019993 - 0.000101 * jc) + std::sin(rad(3 * m)) * 0.000289;
  const double trueLong = l0 + c;  // M
  const double omega = 125.04 - 1934.136 * jc;
  const double appLong = trueLong - 0.00569 - 0.00478 * std::sin(rad(omega));  // P: apparent long
  const double obliqMean =                                                     // Q
      23.0 + (26.0 + (21.448 - jc * (46.815 + jc * (0.00059 - jc * 0.001813))) / 60.0) / 60.0;
  const double obliq = obliqMean + 0.00256 * std::cos(rad(omega));  // R: corrected
  const double y = std::pow(std::tan(rad(obliq / 2.0)), 2.0);       // U: var y

  SunCoordinates s;
  s.declinationDeg = deg(std::asin(std::sin(rad(obliq)) * std::sin(rad(appLong))));           // T
  s.equationOfTimeMin = 4.0 * deg(y * std::sin(2.0 * rad(l0)) - 2.0 * e * std::sin(rad(m)) +  // V
                                  4.0 * e * y * std::sin(rad(m)) * std::cos(2.0 * rad(l0)) -
                                  0.5 * y * y * std::sin(4.0 * rad(l0)) - 1.25 * e * e * std::sin(2.0 * rad(m)));
  return s;
}

}  // namespace

double noaaRefractionDeg(double elev) {  // AF, in arcseconds before the final division
  double arcsec = 0.0;
  if (elev > 85.0) {
    arcsec = 0.0;
  } else if (elev > 5.0) {
    const double t = std::tan(rad(elev));
    arcsec = 58.1 / t - 0.07 / (t * t * t) + 0.000086 / std::pow(t, 5.0);
  } else if (elev > -0.575) {
    arcsec = 1735.0 + elev * (-518.2 + elev * (103.4 + elev * (-12.79 + elev * 0.711)));
  } else {
    arcsec = -20.772 / std::tan(rad(elev));
  }
  return arcsec / 3600.0;
}

SolarPosition solarPosition(std::int64_t unixMs, double latDeg, double lonDeg) {
  const double julianDay = kJulianDayOfUnixEpoch + double(unixMs) / kMsPerDay;  // F
  const double jc = (julianDay - kJ2000) / 36525.0;                             // G
  const SunCoordinates sun = sunCoordinates(jc);

  // AB: true solar time, minutes. The sheet's local time minus its zone is the UTC time of day.
  const double utcMinutes = wrap(double(unixMs), kMsPerDay) / 60'000.0;
  const double trueSolarMin = wrap(utcMinutes + sun.equationOfTimeMin + 4.0 * lonDeg, 1440.0);
  const double hourAngle = trueSolarMin / 4.0 - 180.0;  // AC: [−180, 180), positive after noon

  const double lat = rad(latDeg), dec = rad(sun.declinationDeg), ha = rad(hourAngle);
  const double cosZenith =
      std::clamp(std::sin(lat) * std::sin(dec) + std::cos(lat) * std::cos(dec) * std::cos(ha), -1.0, 1.0);
  const double geometricElevation = 90.0 - deg(std::acos(cosZenith));  // AD, AE

  // AH: clockwise from north; the sheet's acos form, written with atan2.
  const double north = std::sin(dec) * std::cos(lat) - std::cos(dec) * std::sin(lat) * std::cos(ha);
  const double east = -std::cos(dec) * std::sin(ha);

  SolarPosition p;
  p.elevationDeg = geometricElevation + noaaRefractionDeg(geometricElevation);  // AG
  p.zenithDeg = 90.0 - p.elevationDeg;
  p.azimuthDeg = wrap(deg(std::atan2(east, north)), 360.0);
  p.declinationDeg = sun.declinationDeg;
  p.equationOfTimeMin = sun.equationOfTimeMin;
  return p;
}

glm::dvec3 sunDirectionEnu(const SolarPosition& p) {
  const double el = rad(p.elevationDeg), az = rad(p.azimuthDeg);
  return {std::cos(el) * std::sin(az), std::cos(el) * std::cos(az), std::sin(el)};
}

}  // namespace vegstream::geo
