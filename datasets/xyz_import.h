#pragma once
// Import of existing tiles (DESIGN.md "import", the --xyz-elevation form): elevation tiles in
// terrain-RGB or terrarium, optionally imagery tiles, from any source of xyz_source.h — a path
// template "DIR/{z}/{x}/{y}.png", a URL template "https://host/{z}/{x}/{-y}.png", an MBTiles
// file, or a PMTiles archive by path or URL — re-written as a dataset directory
// (dataset_format.h).
//
// Zooms. The elevation source is read at one zoom Z: `maxZoom` when given, else the finest zoom
// the source has (a directory: its files; MBTiles: metadata maxzoom, else its tiles; PMTiles:
// the header's max zoom). A URL template states nothing, so it needs `maxZoom` and `bounds`.
// 256-pixel tiles make a dataset whose max zoom is Z; 512-pixel tiles are split exactly into the
// four 256-pixel tiles of zoom Z + 1 (xyz_source_tiles.h), so the max zoom is Z + 1. Every lower
// zoom down to `minZoom` is rebuilt from the max zoom by the pyramid builder (source tiles at
// lower zooms are ignored, so that all zooms of the dataset agree).
//
// Area. The tiles overlapping `bounds` (else the archive's own bounds, else all the source's
// tiles of zoom Z); a tile the source does not have (a missing file, row or entry; HTTP 404 /
// 410) is no tile there, not an error. The dataset's bounds are the union of the elevation tiles
// written, so the same tiles give the same dataset.json from any kind of source (apart from the
// sources' names).
//
// Imagery is read for the elevation tiles written: 256-pixel tiles at the dataset's max zoom,
// or, when the source has none there, 512-pixel tiles one zoom up, split. Imagery is decoded
// (paletted / greyscale PNG → RGB) and re-encoded. The whole output is written through a
// temporary directory and renamed into place (core/atomic_file.h): a corrupt tile or archive, or
// a URL that fails after the retries, ends the import with an error naming it, and nothing is
// left at `out`.

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/log.h"
#include "core/result.h"
#include "core/task_runner.h"
#include "datasets/dataset_format.h"
#include "datasets/http_fetch.h"
#include "datasets/progress.h"
#include "datasets/xyz_source.h"
#include "geo/bounds.h"

namespace vegstream::datasets {

struct XyzImportOptions {
  // Sources as openXyzSource reads them (xyz_source.h): templates with {z}, {x} and {y} or
  // {-y} (TMS rows), each once, as local paths or http(s) URLs; .mbtiles files; .pmtiles files
  // or URLs.
  std::string elevationTemplate;
  ElevationEncoding encoding = ElevationEncoding::TerrainRgb;  // of the source tiles
  std::optional<std::string> imageryTemplate;

  std::filesystem::path out;  // the dataset directory to create (must not exist or be empty)
  std::string name;           // dataset name; empty: the last component of `out`
  std::string attribution;    // copied into dataset.json

  // How the dataset stores elevation; nullopt: the same encoding as the source.
  std::optional<ElevationEncoding> outputEncoding;
  ImageryFormat imageryFormat = ImageryFormat::Png;  // PNG keeps map renders lossless
  int jpegQuality = 90;

  // Lowest zoom written (the pyramid goes from the dataset's max zoom down to this one).
  // nullopt: down to the zoom at which the data fits in one tile.
  std::optional<int> minZoom;
  // The zoom at which the elevation SOURCE is read ({z}); nullopt: its finest (see above).
  std::optional<int> maxZoom;
  // The area to import (tiles overlapping it); nullopt: the archive's bounds, else everything.
  std::optional<geo::GeoBounds> bounds;
  uint64_t maxTiles = 1'000'000;  // source tiles of the elevation's zoom; more is refused
  HttpFetchOptions http;          // URL templates and PMTiles by URL: retries, time-outs

  int threads = 0;              // 0: all cores (remote sources: at least remoteWorkers)
  int remoteWorkers = 8;        // workers reading a remote source when threads is 0
  TaskRunner* tasks = nullptr;  // runs the workers (outlives the call); null: a pool made for the call
  const std::atomic<bool>* cancel = nullptr;  // set (e.g. by SIGINT): stop between tiles, leave nothing
};

// (done, total) after each tile; total grows as stages (max zoom, each lower zoom) begin.
using XyzProgress = std::function<void(uint64_t done, uint64_t total)>;

// Imports and returns what was written to dataset.json. Errors: InvalidInput (bad template,
// no tiles match, a corrupt tile or archive, a URL that fails — the message names the file or
// URL), NotFound (the template's directory or the archive does not exist), Unsupported (tiles
// neither 256 nor 512 pixels wide, vector archives), Io (cannot write `out`). Progress goes to
// `progress` (the command line passes its ProgressReporter; workers call it concurrently).
Result<DatasetMeta> importXyzTiles(const XyzImportOptions& options, const Logger& log, ProgressSink& progress);
Result<DatasetMeta> importXyzTiles(const XyzImportOptions& options, const Logger& log,
                                   const XyzProgress& progress = {});

}  // namespace vegstream::datasets
