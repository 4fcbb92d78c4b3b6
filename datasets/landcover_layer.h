#pragma once
// The landcover layer of a GDAL import (issue 40, `import --landcover FILE`): the class raster
// opened (band 1), checked over its overview, its scheme stated (--landcover-scheme) or detected
// there, and the codes no scheme knows warned about once. Its tiles are the tile producer's.

#include <cstdint>
#include <memory>

#include "core/log.h"
#include "core/result.h"
#include "datasets/geotiff_import.h"
#include "datasets/landcover_classes.h"
#include "datasets/raster_source.h"
#include "datasets/source_grid.h"

namespace vegstream::datasets {

struct LandcoverLayer {
  std::shared_ptr<RasterSource> source;  // shared: grid points into it
  std::shared_ptr<SourceGrid> grid;
  LandcoverScheme scheme = LandcoverScheme::WorldCover;
};

// Errors (InvalidInput, naming the file): unreadable, no overlap with the DEM, not a class
// raster, a scheme that cannot be detected.
Result<LandcoverLayer> openLandcover(const GeoTiffImportOptions::Landcover& in, const SourceGrid& dem,
                                     uint64_t overviewPixels, const Logger& log);

}  // namespace vegstream::datasets
