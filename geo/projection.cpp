#include "geo/projection.h"

#include <cassert>
#include <cmath>
#include <numbers>
#include <sstream>

#include <GeographicLib/Constants.hpp>
#include <GeographicLib/TransverseMercator.hpp>
#include <GeographicLib/UTMUPS.hpp>

namespace vegstream::geo {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
// UTM's false easting (the central meridian sits at x = 500 km) and zone layout; GeographicLib
// keeps both private to UTMUPS (UTMShift() is the southern false northing).
constexpr double kUtmFalseEasting = 500000.0;
double utmCentralMeridianDeg(int zone) { return 6.0 * zone - 183.0; }
// Tolerance on the Web Mercator latitude limit, so that the exact edge of the tile pyramid
// (computed from y = ±πa and back) is accepted.
constexpr double kLatSlackDeg = 1e-9;

double semiMajor() { return GeographicLib::Constants::WGS84_a(); }

Error outOfRange(const Crs& crs, const Geodetic& p, const std::string& why) {
  std::ostringstream msg;
  msg.precision(10);
  msg << "lat " << p.latDeg << ", lon " << p.lonDeg << " cannot be expressed in " << crs.name() << ": " << why;
  return makeError(ErrorKind::InvalidInput, msg.str());
}

Result<glm::dvec2> toUtm(const Crs& crs, const Geodetic& p) {
  int zone = 0;
  bool northp = true;
  double x = 0.0;
  double y = 0.0;
  try {
    // setzone forces the CRS's zone; UTMUPS then picks the hemisphere from the sign of the
    // latitude, and Transfer moves the northing onto the CRS's hemisphere.
    GeographicLib::UTMUPS::Forward(p.latDeg, p.lonDeg, zone, northp, x, y, crs.utmZone);
    if (northp != crs.north) {
      GeographicLib::UTMUPS::Transfer(zone, northp, x, y, crs.utmZone, crs.north, x, y, zone);
    }
  } catch (const GeographicLib::GeographicErr& e) {
    return outOfRange(crs, p, e.what());
  }
  return glm::dvec2(x, y);
}

}  // namespace

glm::dvec2 lonLatToWebMercator(glm::dvec2 lonLat) {
  assert(std::abs(lonLat.y) <= kWebMercatorMaxLatDeg + kLatSlackDeg);
  const double a = semiMajor();
  // asinh(tan φ) is the Mercator isometric latitude on the sphere; it is better conditioned
  // near the equator than ln(tan(π/4 + φ/2)).
  return {a * lonLat.x * kDeg, a * std::asinh(std::tan(lonLat.y * kDeg))};
}

glm::dvec2 webMercatorToLonLat(glm::dvec2 mercatorM) {
  const double a = semiMajor();
  return {mercatorM.x / a / kDeg, std::atan(std::sinh(mercatorM.y / a)) / kDeg};
}

Result<glm::dvec2> toProjected(const Crs& crs, const Geodetic& p) {
  if (!std::isfinite(p.latDeg) || !std::isfinite(p.lonDeg)) {
    return outOfRange(crs, p, "the coordinates are not finite numbers");
  }
  if (std::abs(p.latDeg) > 90.0) return outOfRange(crs, p, "latitude is outside ±90°");
  switch (crs.kind) {
    case Crs::Kind::Geographic: return glm::dvec2(p.lonDeg, p.latDeg);
    case Crs::Kind::WebMercator: {
      if (std::abs(p.latDeg) > kWebMercatorMaxLatDeg + kLatSlackDeg) {
        return outOfRange(crs, p, "Web Mercator ends at ±85.0511° latitude");
      }
      return lonLatToWebMercator(glm::dvec2(p.lonDeg, p.latDeg));
    }
    case Crs::Kind::Utm: return toUtm(crs, p);
  }
  return makeError(ErrorKind::Internal, "unknown CRS kind");
}

Geodetic fromProjected(const Crs& crs, glm::dvec2 xy, double heightM) {
  Geodetic p;
  p.heightM = heightM;
  switch (crs.kind) {
    case Crs::Kind::Geographic:
      p.lonDeg = xy.x;
      p.latDeg = xy.y;
      break;
    case Crs::Kind::WebMercator: {
      const glm::dvec2 lonLat = webMercatorToLonLat(xy);
      p.lonDeg = lonLat.x;
      p.latDeg = lonLat.y;
      break;
    }
    case Crs::Kind::Utm: {
      assert(crs.utmZone >= 1 && crs.utmZone <= 60);
      // The same series UTMUPS::Reverse evaluates, minus its range checks (which would make
      // this partial): false easting / northing removed, then the zone's central meridian.
      const double falseNorthing = crs.north ? 0.0 : GeographicLib::UTMUPS::UTMShift();
      GeographicLib::TransverseMercator::UTM().Reverse(utmCentralMeridianDeg(crs.utmZone), xy.x - kUtmFalseEasting,
                                                       xy.y - falseNorthing, p.latDeg, p.lonDeg);
      break;
    }
  }
  return p;
}

Result<glm::dvec2> reproject(const Crs& from, const Crs& to, glm::dvec2 xy) {
  if (from == to) return xy;
  return toProjected(to, fromProjected(from, xy));
}

}  // namespace vegstream::geo
