#pragma once
// Heights on a regular grid as plain data (terrain/ does not read files): either a regular
// latitude/longitude grid (an EPSG:4326 DEM such as Zion's SRTM tile) or the Web Mercator pixel
// grid of one zoom (a dataset's tiles, streaming/dataset_snapshot.h). Nodata samples are NaN.

#include <cmath>
#include <cstddef>
#include <vector>

#include <glm/vec2.hpp>

namespace vegstream::terrain {

enum class GridCrs {
  Geographic,   // first/step in degrees: x = longitude, y = latitude
  WebMercator,  // first/step in EPSG:3857 metres
};

struct HeightGrid {
  GridCrs crs = GridCrs::Geographic;
  int width = 0;
  int height = 0;
  double lonFirst = 0.0;       // x of the centre of column 0 (degrees or metres, see crs)
  double latFirst = 0.0;       // y of the centre of row 0 (row 0 is the north edge)
  double lonStep = 0.0;        // x per column (> 0)
  double latStep = 0.0;        // y per row (< 0 for north-up rasters)
  std::vector<float> heights;  // row-major, metres MSL, NaN = nodata

  float at(int col, int row) const {
    return heights[static_cast<size_t>(row) * static_cast<size_t>(width) + static_cast<size_t>(col)];
  }
  // Longitude/latitude (degrees) of fractional grid coordinates, and back.
  glm::dvec2 lonLatAt(double col, double row) const;
  glm::dvec2 gridAt(double lonDeg, double latDeg) const;
  double centreLon() const { return lonLatAt(0.5 * (width - 1), 0.5 * (height - 1)).x; }
  double centreLat() const { return lonLatAt(0.5 * (width - 1), 0.5 * (height - 1)).y; }

  // Bilinear height at fractional grid coordinates, NaN if any neighbour is nodata or the
  // point lies outside the grid.
  double sample(double col, double row) const;
  // Bilinear height at a longitude/latitude (degrees).
  double sampleLonLat(double lon, double lat) const {
    const glm::dvec2 g = gridAt(lon, lat);
    return sample(g.x, g.y);
  }
};

}  // namespace vegstream::terrain
