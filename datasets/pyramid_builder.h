#pragma once
// Builds the lower zooms of a dataset from its finest zoom (dataset_format.h layout): every
// tile at zoom z−1 is the 2×2 downsample of its four children at z. Heights: the mean of the
// valid children pixels of each 2×2 block (nodata only where all four are nodata); colour: the
// mean of the valid (alpha ≠ 0) pixels; NDVI (when the dataset has the layer): the mean of the
// valid NDVI values; landcover (when the dataset has the layer): the mode of the valid classes,
// ties to the smallest code (landcover.h), never a mean. Used by both importers (GeoTIFF and XYZ
// tiles).

#include <filesystem>

#include "core/result.h"
#include "core/task_runner.h"
#include "datasets/dataset_format.h"
#include "datasets/progress.h"

namespace vegstream::datasets {

struct PyramidOptions {
  int threads = 0;              // 0: all cores
  TaskRunner* tasks = nullptr;  // runs the workers (outlives the call); null: a pool made for the call
  int jpegQuality = 90;         // for JPEG imagery
};

// Reads the tiles present at meta.maxZoom under `dir` (elevation/, imagery/ when meta.imagery is
// set, ndvi/ when meta.ndvi is, landcover/ when meta.landcover is), writes zooms meta.maxZoom−1 …
// meta.minZoom, and adds the tiles written and their bytes to meta.elevationTiles /
// imageryTiles / ndviTiles / landcoverTiles / bytes (the max-zoom tiles are the caller's to
// count). Tiles are decoded with meta.elevationEncoding. Reports each tile to
// `progress` (addTotal once per zoom, before that zoom's tiles). Does not write dataset.json.
// Errors: a tile that cannot be decoded (InvalidInput, naming it) or written (Io).
Status buildLowerZooms(const std::filesystem::path& dir, DatasetMeta& meta, ProgressSink& progress,
                       const PyramidOptions& options = {});

}  // namespace vegstream::datasets
