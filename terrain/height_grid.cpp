#include "terrain/height_grid.h"

#include "geo/projection.h"

#include <algorithm>
#include <limits>

namespace vegstream::terrain {

glm::dvec2 HeightGrid::lonLatAt(double col, double row) const {
  const glm::dvec2 xy{lonFirst + lonStep * col, latFirst + latStep * row};
  return crs == GridCrs::Geographic ? xy : geo::webMercatorToLonLat(xy);
}

glm::dvec2 HeightGrid::gridAt(double lonDeg, double latDeg) const {
  const glm::dvec2 xy =
      crs == GridCrs::Geographic ? glm::dvec2{lonDeg, latDeg} : geo::lonLatToWebMercator({lonDeg, latDeg});
  return {(xy.x - lonFirst) / lonStep, (xy.y - latFirst) / latStep};
}

double HeightGrid::sample(double col, double row) const {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (!(col >= 0.0 && row >= 0.0 && col <= width - 1 && row <= height - 1)) return nan;
  const int c0 = std::min(static_cast<int>(col), width - 2 < 0 ? 0 : width - 2);
  const int r0 = std::min(static_cast<int>(row), height - 2 < 0 ? 0 : height - 2);
  const int c1 = std::min(c0 + 1, width - 1), r1 = std::min(r0 + 1, height - 1);
  const double fx = col - c0, fy = row - r0;
  const double h00 = at(c0, r0), h10 = at(c1, r0), h01 = at(c0, r1), h11 = at(c1, r1);
  const double top = h00 + (h10 - h00) * fx;
  const double bottom = h01 + (h11 - h01) * fx;
  return top + (bottom - top) * fy;  // NaN propagates from any nodata neighbour
}

}  // namespace vegstream::terrain
