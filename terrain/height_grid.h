#pragma once
// Heights on a regular latitude/longitude grid (an EPSG:4326 DEM such as Zion's SRTM tile),
// as plain data: terrain/ does not read files. Nodata samples are NaN.

#include <cmath>
#include <cstddef>
#include <vector>

namespace vegstream::terrain {

struct HeightGrid {
  int width = 0;
  int height = 0;
  double lonFirst = 0.0;  // longitude of the centre of column 0 (degrees)
  double latFirst = 0.0;  // latitude of the centre of row 0 (degrees; row 0 is the north edge)
  double lonStep = 0.0;   // degrees per column (> 0)
  double latStep = 0.0;   // degrees per row (< 0 for north-up rasters)
  std::vector<float> heights;  // row-major, metres MSL, NaN = nodata

  float at(int col, int row) const {
    return heights[static_cast<size_t>(row) * static_cast<size_t>(width) + static_cast<size_t>(col)];
  }
  double lonAt(double col) const { return lonFirst + lonStep * col; }
  double latAt(double row) const { return latFirst + latStep * row; }
  double centreLon() const { return lonAt(0.5 * (width - 1)); }
  double centreLat() const { return latAt(0.5 * (height - 1)); }

  // Bilinear height at fractional grid coordinates, NaN if any neighbour is nodata or the
  // point lies outside the grid.
  double sample(double col, double row) const;
  // Bilinear height at a longitude/latitude (degrees).
  double sampleLonLat(double lon, double lat) const { return sample((lon - lonFirst) / lonStep, (lat - latFirst) / latStep); }
};

}  // namespace vegstream::terrain
