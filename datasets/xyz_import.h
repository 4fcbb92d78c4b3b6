#pragma once
// Import of existing XYZ tiles (DESIGN.md "import", the --xyz-elevation form): elevation tiles
// in terrain-RGB or terrarium, optionally imagery tiles, found through a path template such as
// "DIR/{z}/{x}/{y}.png", re-written as a dataset directory (dataset_format.h).
//
// The zoom range of the source is found from the files that match the template; the finest
// zoom that has elevation tiles becomes the dataset's max zoom, and every lower zoom down to
// `minZoom` is rebuilt from it by the pyramid builder (source tiles at lower zooms are ignored,
// so that all zooms of the dataset agree). Imagery is decoded (paletted / greyscale PNG → RGB)
// and written at the elevation's max zoom. The whole output is written through a temporary
// directory and renamed into place (core/atomic_file.h): a corrupt tile ends the import with an
// InvalidInput error naming the file, and nothing is left at `out`.

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
#include "datasets/progress.h"

namespace vegstream::datasets {

struct XyzImportOptions {
  // Path templates with the placeholders {z}, {x} and {y} (each exactly once, in the path's
  // last three components, e.g. "tiles/{z}/{x}/{y}.png"). "{-y}" (TMS rows) is not supported.
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

  // Lowest zoom written (the pyramid goes from the source's finest zoom down to this one).
  // nullopt: down to the zoom at which the data fits in one tile.
  std::optional<int> minZoom;

  int threads = 0;              // 0: all cores
  TaskRunner* tasks = nullptr;  // runs the workers (outlives the call); null: a pool made for the call
};

// (done, total) after each tile; total grows as stages (max zoom, each lower zoom) begin.
using XyzProgress = std::function<void(uint64_t done, uint64_t total)>;

// Imports and returns what was written to dataset.json. Errors: InvalidInput (bad template,
// no tiles match, a corrupt tile — the message names the file), NotFound (the template's
// directory does not exist), Io (cannot write `out`). Progress goes to `progress` (the command
// line passes its ProgressReporter; workers call it concurrently).
Result<DatasetMeta> importXyzTiles(const XyzImportOptions& options, const Logger& log, ProgressSink& progress);
Result<DatasetMeta> importXyzTiles(const XyzImportOptions& options, const Logger& log,
                                   const XyzProgress& progress = {});

// The tiles that match a template, sorted; exposed for tests and for `vegstream info`-like tools.
struct XyzTileFile {
  geo::TileId id;
  std::filesystem::path path;
};
Result<std::vector<XyzTileFile>> findXyzTiles(const std::string& pathTemplate);

}  // namespace vegstream::datasets
