#pragma once
// Geodetic ↔ projected coordinates for the CRSs of crs.h (GeographicLib underneath).
//
//   Geographic   x = longitude, y = latitude, degrees (identity)
//   WebMercator  EPSG:3857 metres. GeographicLib has no Web Mercator, and its closed form is
//                the *spherical* Mercator formula evaluated on the WGS 84 semi-major axis
//                a = 6 378 137 m (that is what EPSG:3857 defines): x = a·λ, y = a·asinh(tan φ).
//   Utm          GeographicLib::UTMUPS with the CRS's zone forced, so a point outside the
//                zone's 6° strip still lands in that zone's grid (data are often delivered in
//                one zone across a boundary); the hemisphere is forced too, so a northern CRS
//                continues across the equator with negative northings.

#include <glm/vec2.hpp>

#include "core/result.h"
#include "geo/crs.h"
#include "geo/geodetic.h"

namespace vegstream::geo {

// The latitude where EPSG:3857 becomes square (y = ±π·a): atan(sinh(π)) = 85.05112877980659°.
inline constexpr double kWebMercatorMaxLatDeg = 85.05112877980659;
// Half the width of the EPSG:3857 world, π·a metres.
inline constexpr double kWebMercatorHalfWorldM = 20037508.342789244;

// The Web Mercator closed form itself, for the tile maths: lonLat.x = longitude, .y = latitude
// in degrees, |latitude| ≤ kWebMercatorMaxLatDeg (asserted, with 1e-9° slack).
glm::dvec2 lonLatToWebMercator(glm::dvec2 lonLat);
glm::dvec2 webMercatorToLonLat(glm::dvec2 mercatorM);

// Errors (ErrorKind::InvalidInput), each naming the point and the CRS: a non-finite input,
// a latitude outside ±90°, beyond ±kWebMercatorMaxLatDeg for Web Mercator, or a point so far
// outside a UTM zone that GeographicLib refuses it (easting outside 0 … 1000 km, northing
// outside the hemisphere's extended range). The height is ignored.
Result<glm::dvec2> toProjected(const Crs& crs, const Geodetic& p);

// Total: every finite (x, y) gives a position (UTM through GeographicLib's transverse Mercator
// without range checks, so a corner slightly outside a zone's nominal grid still converts).
// heightM is set to `heightM`. Longitudes come back in [-180, 180] for UTM and as x / a
// (unwrapped) for Web Mercator and geographic.
Geodetic fromProjected(const Crs& crs, glm::dvec2 xy, double heightM = 0.0);

// from → geodetic → to, e.g. an output Web Mercator pixel centre into a UTM imagery file.
Result<glm::dvec2> reproject(const Crs& from, const Crs& to, glm::dvec2 xy);

}  // namespace vegstream::geo
