#pragma once
// The canopy layer of a GDAL import (issue 41 item 3, `import --canopy-height FILE`): the canopy
// height model opened (band 1, heights: a band declaring feet is converted to metres), checked
// over its overview and again in every tile's window (canopy.h checkCanopyRaster), sampled at the
// zoom that keeps its own pixels (naturalZoom of its pixel size, at most kMaxAutoZoom) over the
// part it shares with the DEM (bilinear over the valid neighbours, no data where less than half
// the weight is valid), then reduced to the dataset's min zoom (the highest of each 2 × 2).

#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "core/log.h"
#include "core/result.h"
#include "core/task_runner.h"
#include "datasets/dataset_format.h"
#include "datasets/progress.h"
#include "datasets/raster_source.h"
#include "datasets/source_grid.h"
#include "geo/crs.h"

namespace vegstream::datasets {

struct CanopyLayer {
  std::string file;
  std::shared_ptr<RasterSource> source;  // shared: grid points into it
  std::shared_ptr<SourceGrid> grid;
  int zoom = 0;  // the zoom its tiles are written at
};

// Errors (InvalidInput, naming the file): unreadable, no CRS (say --canopy-height-crs), more than
// one band, no overlap with the DEM, implausible heights (canopy.h).
Result<CanopyLayer> openCanopy(const std::string& file, const std::optional<geo::Crs>& crs, const SourceGrid& dem,
                               uint64_t overviewPixels, const Logger& log);

// Writes canopy/{z}/{x}/{y}.png under `dir` at layer.zoom over the CHM ∩ the DEM, and the pyramid
// down to meta.minZoom; sets meta.canopyZoom, adds meta.canopyTiles and meta.bytes. More tiles
// than maxTiles at layer.zoom: InvalidInput. threads / tasks as in parallelFor.
Status importCanopyTiles(const std::filesystem::path& dir, const CanopyLayer& layer, const geo::GeoBounds& demExtent,
                         uint64_t maxTiles, int threads, TaskRunner* tasks, ProgressSink& progress, DatasetMeta& meta);

}  // namespace vegstream::datasets
