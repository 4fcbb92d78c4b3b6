#pragma once
// Opening a dataset wherever it is: the one place that turns the user's DATASET argument into
// a TileSource, and reads its dataset.json through that source.
//
//   "http://…", "https://…"  → HttpTileSource (http_tile_source.h)
//   anything else            → LocalTileSource over that directory (local_tile_source.h)

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "core/log.h"
#include "core/task_runner.h"
#include "core/result.h"
#include "datasets/dataset_format.h"
#include "streaming/http_tile_source.h"
#include "streaming/tile_source.h"

namespace vegstream::streaming {

struct OpenSourceOptions {
  HttpSourceOptions http;       // for URLs; its baseUrl is replaced by the location
  int localIoThreads = 2;       // for directories: reads at once
  Logger log;                   // given to the HTTP source when http.log is null
  TaskRunner* tasks = nullptr;  // the sources' I/O (outlives the source); null: each makes its own pool
};

// True for "http://…" and "https://…" (case-insensitive scheme).
bool isHttpLocation(const std::string& location);

// Errors: InvalidInput for a malformed URL; NotFound when a directory does not exist or is not
// a directory; Io when the HTTP cache directory cannot be opened. The dataset itself is not
// read here (readMetaFrom does that).
Result<std::shared_ptr<TileSource>> openTileSource(const std::string& location, const OpenSourceOptions& options);

// readText("dataset.json") → parseDatasetMeta, the errors naming the source's file or URL; a
// tile_size other than datasets::kTileSize is InvalidInput (what streams is laid out for it).
Result<datasets::DatasetMeta> readMetaFrom(TileSource& source);

// How errors name the source's dataset.json: "DIR/dataset.json" or "URL/dataset.json".
std::string datasetJsonName(const TileSource& source);

}  // namespace vegstream::streaming
