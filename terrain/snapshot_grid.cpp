#include "terrain/snapshot_grid.h"

#include "geo/projection.h"

namespace vegstream::terrain {

HeightGrid heightGridFrom(const streaming::HeightMosaic& mosaic) {
  HeightGrid g;
  g.crs = GridCrs::WebMercator;
  g.width = mosaic.width;
  g.height = mosaic.height;
  g.lonFirst = mosaic.x0;
  g.latFirst = mosaic.y0;
  g.lonStep = mosaic.pixelM;
  g.latStep = -mosaic.pixelM;
  g.heights = mosaic.heights;
  return g;
}

std::function<glm::vec2(double, double)> imageryUv(const streaming::MercatorRaster& imagery) {
  const double west = imagery.x0 - 0.5 * imagery.pixelM;
  const double north = imagery.y0 + 0.5 * imagery.pixelM;
  const double width = imagery.width * imagery.pixelM;
  const double height = imagery.height * imagery.pixelM;
  return [=](double lonDeg, double latDeg) {
    const glm::dvec2 xy = geo::lonLatToWebMercator({lonDeg, latDeg});
    return glm::vec2(static_cast<float>((xy.x - west) / width), static_cast<float>((north - xy.y) / height));
  };
}

}  // namespace vegstream::terrain
