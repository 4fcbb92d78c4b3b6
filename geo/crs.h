#pragma once
// Coordinate reference systems: any CRS PROJ knows, through GDAL's OGRSpatialReference (the
// field's standard; no table of our own). A Crs is an immutable, cheap-to-copy value naming one
// CRS; projection.h transforms between it and WGS 84 longitude/latitude.
//
// Where a Crs comes from:
//   - a raster's own georeference (datasets/raster_source.h hands over its WKT);
//   - the user: `--dem-crs EPSG:27700`, `--imagery-crs 26912`, WKT, PROJJSON or a PROJ string
//     (OGRSpatialReference::SetFromUserInput), for files whose CRS is missing or wrong;
//   - code: wgs84Crs(), webMercatorCrs(), utmCrs().
// Axis order is always the GIS one: x = longitude / easting, y = latitude / northing.

#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "core/result.h"

namespace vegstream::geo {

class Crs {
 public:
  Crs();  // WGS 84 geographic (EPSG:4326)

  // "EPSG:27700", "epsg:4326", "4326", a WKT or PROJJSON text, or a PROJ string. Errors
  // (InvalidInput) name the text and PROJ's reason.
  static Result<Crs> fromUserInput(std::string_view text);
  // A CRS as GDAL reports a raster's (WKT). Errors as fromUserInput.
  static Result<Crs> fromWkt(const std::string& wkt);

  // "OSGB36 / British National Grid (EPSG:27700)" — for messages and dataset.json.
  std::string name() const;
  // "EPSG:27700", or "" when PROJ finds no EPSG code for it.
  std::string code() const;
  std::optional<int> epsg() const;
  // PROJJSON (PROJ ≥ 6.2), for dataset.json when the CRS has no EPSG code.
  const std::string& projjson() const;
  const std::string& wkt() const;
  bool isGeographic() const;   // longitude/latitude degrees
  bool isWgs84LonLat() const;  // EPSG:4326 itself: projection is the identity
  bool isWebMercator() const;  // EPSG:3857 (or an alias): the closed form of projection.h
  // One number per CRS value made (never reused while the process runs): the key of the
  // per-thread transformation caches.
  uint64_t id() const;

  // The same CRS (OGRSpatialReference::IsSame), e.g. EPSG:32612 and its WKT.
  bool operator==(const Crs& other) const;

  struct Data;

 private:
  explicit Crs(std::shared_ptr<const Data> d) : d_(std::move(d)) {}
  std::shared_ptr<const Data> d_;
};

Crs wgs84Crs();
Crs webMercatorCrs();
Crs utmCrs(int zone, bool north);  // WGS 84 / UTM, zone in 1 … 60 (asserted)

// The standard UTM zone (1 … 60) of a point, with the Norway / Svalbard exceptions: the zone
// a dataset centred there would naturally be delivered in. Latitude within ±90 (asserted).
int standardUtmZone(double latDeg, double lonDeg);

}  // namespace vegstream::geo
