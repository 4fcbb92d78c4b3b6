#include "geo/projection.h"

#include <cassert>
#include <cmath>
#include <numbers>
#include <sstream>

#include <limits>
#include <memory>
#include <vector>

#include <GeographicLib/Constants.hpp>
#include <ogr_spatialref.h>

#include "geo/gdal_quiet.h"

namespace vegstream::geo {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
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

// One OGR transformation per (CRS, direction) per thread: OGRCoordinateTransformation is not
// thread-safe, and making one costs PROJ's pipeline search (milliseconds), so each thread keeps
// the few it used last.
class TransformCache {
 public:
  OGRCoordinateTransformation* get(const Crs& crs, bool toLonLat) {
    for (auto& e : entries_)
      if (e.id == crs.id() && e.toLonLat == toLonLat) return e.t.get();
    GdalQuiet quiet;
    OGRSpatialReference a, b;
    a.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    b.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    if (a.importFromWkt(crs.wkt().c_str()) != OGRERR_NONE || b.importFromEPSG(4326) != OGRERR_NONE) return nullptr;
    std::unique_ptr<OGRCoordinateTransformation> t(
        toLonLat ? OGRCreateCoordinateTransformation(&a, &b) : OGRCreateCoordinateTransformation(&b, &a));
    if (!t) return nullptr;
    if (entries_.size() >= 8) entries_.erase(entries_.begin());
    entries_.push_back({crs.id(), toLonLat, std::move(t)});
    return entries_.back().t.get();
  }

 private:
  struct Entry {
    uint64_t id;
    bool toLonLat;
    std::unique_ptr<OGRCoordinateTransformation> t;
  };
  std::vector<Entry> entries_;
};

OGRCoordinateTransformation* transformFor(const Crs& crs, bool toLonLat) {
  thread_local TransformCache cache;
  return cache.get(crs, toLonLat);
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
  if (crs.isWgs84LonLat()) return glm::dvec2(p.lonDeg, p.latDeg);
  if (crs.isWebMercator()) {
    if (std::abs(p.latDeg) > kWebMercatorMaxLatDeg + kLatSlackDeg) {
      return outOfRange(crs, p, "Web Mercator ends at ±85.0511° latitude");
    }
    return lonLatToWebMercator(glm::dvec2(p.lonDeg, p.latDeg));
  }
  OGRCoordinateTransformation* t = transformFor(crs, false);
  if (!t) return outOfRange(crs, p, "PROJ has no transformation from WGS 84 to it");
  double x = p.lonDeg, y = p.latDeg;
  int ok = 0;
  {
    GdalQuiet quiet;
    if (!t->Transform(1, &x, &y, nullptr, nullptr, &ok) || !ok || !std::isfinite(x) || !std::isfinite(y))
      return outOfRange(crs, p, "PROJ cannot transform the point (outside the CRS's area)");
  }
  return glm::dvec2(x, y);
}

Geodetic fromProjected(const Crs& crs, glm::dvec2 xy, double heightM) {
  Geodetic p;
  p.heightM = heightM;
  if (crs.isWgs84LonLat()) {
    p.lonDeg = xy.x;
    p.latDeg = xy.y;
    return p;
  }
  if (crs.isWebMercator()) {
    const glm::dvec2 lonLat = webMercatorToLonLat(xy);
    p.lonDeg = lonLat.x;
    p.latDeg = lonLat.y;
    return p;
  }
  p.lonDeg = p.latDeg = std::numeric_limits<double>::quiet_NaN();
  OGRCoordinateTransformation* t = transformFor(crs, true);
  if (!t || !std::isfinite(xy.x) || !std::isfinite(xy.y)) return p;
  double x = xy.x, y = xy.y;
  int ok = 0;
  GdalQuiet quiet;
  if (t->Transform(1, &x, &y, nullptr, nullptr, &ok) && ok) {
    p.lonDeg = x;
    p.latDeg = y;
  }
  return p;
}

Result<glm::dvec2> reproject(const Crs& from, const Crs& to, glm::dvec2 xy) {
  if (from == to) return xy;
  return toProjected(to, fromProjected(from, xy));
}

}  // namespace vegstream::geo
