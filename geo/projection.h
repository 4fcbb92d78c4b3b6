#pragma once
// Geodetic (WGS 84 longitude/latitude) ↔ the coordinates of any CRS of crs.h.
//
//   EPSG:4326    identity (x = longitude, y = latitude).
//   EPSG:3857    the closed form: the *spherical* Mercator formula on the WGS 84 semi-major axis
//                a = 6 378 137 m (what EPSG:3857 defines): x = a·λ, y = a·asinh(tan φ); exact
//                and fast, since every tile position goes through it.
//   anything else: PROJ's transformation as GDAL chooses it (OGRCoordinateTransformation,
//                GIS axis order; the best operation PROJ knows without network grids, e.g. the
//                Helmert transformation for OSGB36 → WGS 84, null for NAD83 → WGS 84). One per
//                CRS per thread is kept (they are not thread-safe and slow to make).
// Heights are not transformed: the raster's values are heights above its own vertical datum.

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
// a latitude outside ±90°, beyond ±kWebMercatorMaxLatDeg for Web Mercator, or a point PROJ
// cannot transform. The height is ignored.
Result<glm::dvec2> toProjected(const Crs& crs, const Geodetic& p);

// The position of (x, y); latitude and longitude NaN when PROJ cannot transform it (callers
// check std::isfinite). heightM is set to `heightM`. Longitudes come back as PROJ gives them,
// and as x / a (unwrapped) for Web Mercator and as x for EPSG:4326.
Geodetic fromProjected(const Crs& crs, glm::dvec2 xy, double heightM = 0.0);

// from → geodetic → to, e.g. an output Web Mercator pixel centre into a UTM imagery file.
Result<glm::dvec2> reproject(const Crs& from, const Crs& to, glm::dvec2 xy);

}  // namespace vegstream::geo
