#pragma once
// Axis-aligned boxes: in longitude/latitude (dataset extents, tile extents) and in projected
// metres (a GeoTIFF's extent in its own CRS, a tile in EPSG:3857).

#include <glm/vec2.hpp>

namespace vegstream::geo {

// Degrees. westDeg > eastDeg means the box crosses the antimeridian.
struct GeoBounds {
  double westDeg = 0.0;
  double southDeg = 0.0;
  double eastDeg = 0.0;
  double northDeg = 0.0;

  bool crossesAntimeridian() const { return westDeg > eastDeg; }
  double widthDeg() const { return crossesAntimeridian() ? eastDeg + 360.0 - westDeg : eastDeg - westDeg; }
  double heightDeg() const { return northDeg - southDeg; }
  // x = longitude (in [-180, 180] when the box crosses the antimeridian), y = latitude.
  glm::dvec2 centre() const {
    double lon = westDeg + 0.5 * widthDeg();
    if (lon > 180.0) lon -= 360.0;
    return {lon, 0.5 * (southDeg + northDeg)};
  }
  bool operator==(const GeoBounds&) const = default;
};

// Metres in some projected CRS; min = (west, south), max = (east, north).
struct ProjectedBounds {
  glm::dvec2 min{0.0};
  glm::dvec2 max{0.0};

  glm::dvec2 size() const { return max - min; }
  glm::dvec2 centre() const { return 0.5 * (min + max); }
  bool operator==(const ProjectedBounds&) const = default;
};

}  // namespace vegstream::geo
