// The landcover layer of a GDAL import (landcover_layer.h): opened, checked over its overview,
// its scheme stated or detected there, unknown codes warned about once.
#include "datasets/landcover_layer.h"

#include <string>
#include <utility>

#include "datasets/landcover.h"
#include "datasets/message.h"

namespace vegstream::datasets {

Result<LandcoverLayer> openLandcover(const GeoTiffImportOptions::Landcover& in, const SourceGrid& dem,
                                     uint64_t overviewPixels, const Logger& log) {
  auto opened =
      openGridded(in.file, {.flag = "--landcover", .crsFlag = "--landcover-crs", .assumeCrs = in.crs, .bands = {1}});
  if (!opened) return opened.error();
  LandcoverLayer l{opened->source, opened->grid};
  if (!extentsOverlap(dem.extent(), l.grid->extent()))
    return makeError(ErrorKind::InvalidInput, concat("the landcover ", in.file, " (", extentText(l.grid->extent()),
                                                     ") and the DEM (", extentText(dem.extent()), ") do not overlap"));
  auto overview = l.source->readOverview(overviewPixels);
  if (!overview) return overview.error();
  if (auto s = checkClassRaster(*overview); !s) return s.error();
  const ClassHistogram histogram = classHistogram(*overview);
  if (in.scheme) {
    l.scheme = *in.scheme;
  } else {
    auto scheme = detectLandcoverScheme(histogram, in.file);
    if (!scheme) return scheme.error();
    l.scheme = *scheme;
  }
  const std::string unknown = unknownClassesWarning(unknownClasses(histogram, l.scheme), l.scheme);
  if (!unknown.empty()) log->warn("{}: {}", in.file, unknown);
  log->info("{}: landcover, {} classes, {} ({:.1f} m pixels)", in.file, toString(l.scheme), l.grid->crs().name(),
            l.grid->pixelSizeM());
  return l;
}

}  // namespace vegstream::datasets
