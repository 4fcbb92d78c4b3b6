#pragma once
// `vegstream info DATASET`: what a dataset directory holds, as JSON on stdout (name, CRS of the
// sources, bounds, zoom range, height range, tile counts per zoom, bytes, and "tilejson": the
// TileJSON files beside it, layer → file name relative to the dataset, datasets/tilejson.h;
// {} for datasets made before them), so that scripts and people can check an import without
// opening the tiles.

#include <string>

#include "core/log.h"

namespace vegstream::app {

struct InfoOptions {
  std::string dataset;
};

// Exit code: 0, or 2 when the directory is missing or its dataset.json is bad (one message).
int runInfo(const InfoOptions& options, const Logger& log);

}  // namespace vegstream::app
