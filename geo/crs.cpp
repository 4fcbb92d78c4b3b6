#include "geo/crs.h"

#include <algorithm>
#include <cassert>
#include <cctype>
#include <charconv>
#include <utility>

#include <GeographicLib/UTMUPS.hpp>

namespace vegstream::geo {
namespace {

constexpr int kUtmNorthFirst = 32601;
constexpr int kUtmSouthFirst = 32701;
constexpr int kUtmZones = 60;

std::string_view trim(std::string_view s) {
  const auto blank = [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; };
  while (!s.empty() && blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && blank(s.back())) s.remove_suffix(1);
  return s;
}

bool startsWithNoCase(std::string_view s, std::string_view prefix) {
  if (s.size() < prefix.size()) return false;
  return std::equal(prefix.begin(), prefix.end(), s.begin(), [](char a, char b) {
    return std::tolower(static_cast<unsigned char>(a)) == std::tolower(static_cast<unsigned char>(b));
  });
}

}  // namespace

std::string Crs::code() const { return "EPSG:" + std::to_string(epsg); }

std::string Crs::name() const {
  switch (kind) {
    case Kind::Geographic: return epsg == 4269 ? "NAD83 read as WGS 84 (" + code() + ")" : "WGS 84 (" + code() + ")";
    case Kind::WebMercator: return "WGS 84 / Pseudo-Mercator (" + code() + ")";
    case Kind::Utm: return "WGS 84 / UTM zone " + std::to_string(utmZone) + (north ? "N" : "S") + " (" + code() + ")";
  }
  return code();
}

Crs wgs84Crs() { return Crs{Crs::Kind::Geographic, 4326, 0, true}; }

Crs webMercatorCrs() { return Crs{Crs::Kind::WebMercator, 3857, 0, true}; }

Crs utmCrs(int zone, bool north) {
  assert(zone >= 1 && zone <= kUtmZones);
  return Crs{Crs::Kind::Utm, (north ? kUtmNorthFirst : kUtmSouthFirst) + zone - 1, zone, north};
}

int standardUtmZone(double latDeg, double lonDeg) {
  assert(latDeg >= -90.0 && latDeg <= 90.0);
  // GeographicLib answers 0 (UPS) beyond 80°S / 84°N; a UTM zone is still wanted there, so
  // the latitude is clamped into the UTM band, which keeps the Svalbard exception at 84°N.
  const double lat = std::clamp(latDeg, -80.0, 83.999999);
  return GeographicLib::UTMUPS::StandardZone(lat, lonDeg);
}

Result<Crs> crsFromEpsg(int epsg, const WarningSink& warn) {
  switch (epsg) {
    case 4326: return wgs84Crs();
    case 4269:
      // NAD83 is tied to the North American plate, WGS 84 (G1762+) to ITRF: they drift apart by
      // a couple of cm a year and differ by about 1 m today — far below a DEM or imagery pixel
      // of the data people fly over, so no datum shift is applied.
      if (warn) {
        warn(
            "EPSG:4269 (NAD83) is read as WGS 84 without a datum shift: the two differ by "
            "about 1 m horizontally (sub-metre to ~2 m depending on realisation and place), "
            "below the resolution of the data");
      }
      return Crs{Crs::Kind::Geographic, 4269, 0, true};
    case 3857:
    case 900913:  // the unofficial "GOOGLE" code still found in older files
    case 3785:    // the deprecated EPSG code of the same projection
      return webMercatorCrs();
    default: break;
  }
  if (epsg >= kUtmNorthFirst && epsg < kUtmNorthFirst + kUtmZones) {
    return utmCrs(epsg - kUtmNorthFirst + 1, true);
  }
  if (epsg >= kUtmSouthFirst && epsg < kUtmSouthFirst + kUtmZones) {
    return utmCrs(epsg - kUtmSouthFirst + 1, false);
  }
  return makeError(ErrorKind::Unsupported, "EPSG:" + std::to_string(epsg) +
                                               " is not supported; vegstream reads EPSG:4326, 4269, 3857 and UTM "
                                               "326xx/327xx (WGS 84 / UTM zones 1-60 north/south)");
}

Result<Crs> parseCrs(std::string_view text, const WarningSink& warn) {
  std::string_view digits = trim(text);
  if (startsWithNoCase(digits, "EPSG:")) digits.remove_prefix(5);
  int epsg = 0;
  const char* end = digits.data() + digits.size();
  const auto [ptr, ec] = std::from_chars(digits.data(), end, epsg);
  if (digits.empty() || ec != std::errc() || ptr != end || epsg <= 0) {
    // Appended piecewise: GCC 12 at -O3 reports a false -Wrestrict on "'" + std::string(...).
    std::string message = "'";
    message.append(text);
    message.append(
        "' is not a CRS vegstream understands; write an EPSG code such as EPSG:4326 "
        "or EPSG:32612");
    return makeError(ErrorKind::InvalidInput, std::move(message));
  }
  return crsFromEpsg(epsg, warn);
}

}  // namespace vegstream::geo
