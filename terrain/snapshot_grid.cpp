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

}  // namespace vegstream::terrain
