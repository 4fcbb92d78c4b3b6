#pragma once
// The last steps that every writer of a dataset shares once its finest zoom is on disk (the
// XYZ importer and the synthetic generator): pick the min zoom, build the lower zooms with the
// pyramid builder, write the TileJSON files (tilejson.h) and dataset.json.

#include <cstdint>
#include <filesystem>
#include <vector>

#include "core/result.h"
#include "core/task_runner.h"
#include "datasets/dataset_format.h"
#include "datasets/progress.h"

namespace vegstream::datasets {

// The highest zoom ≤ the tiles' zoom at which all `tiles` (one zoom, non-empty) share one
// ancestor: the coarsest zoom worth writing by default.
int singleTileZoom(const std::vector<geo::TileId>& tiles);

// Size of a file, 0 when it cannot be read.
uint64_t fileBytes(const std::filesystem::path& path);

// meta: maxZoom / minZoom set, the max-zoom tiles already counted in elevationTiles /
// imageryTiles / ndviTiles / bytes. Builds zooms maxZoom−1 … minZoom under dir, then writes the
// TileJSON files (tilejson.h) and, last, dataset.json.
// `threads` and `tasks` as in parallelFor.
Result<DatasetMeta> finishDataset(const std::filesystem::path& dir, DatasetMeta meta, ProgressSink& progress,
                                  int threads, int jpegQuality, TaskRunner* tasks = nullptr);

// The dataset name a user means by an output path ("out/grand/" → "grand").
std::string defaultDatasetName(const std::filesystem::path& out);

}  // namespace vegstream::datasets
