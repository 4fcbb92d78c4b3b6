#pragma once
// The tile check of a dataset: whether bytes fetched for a
// dataset-relative path are the tile that path names — they decode, in the layer's encoding
// (elevation: the dataset's elevation encoding; imagery: PNG/JPEG/WebP RGB(A); NDVI and
// landcover: one-channel 8-bit PNG; canopy: one-channel 16-bit PNG), at the dataset's tile size.
// What the HTTP source's disk cache keeps (nothing that does not pass it is cached, so an error
// page from a proxy cannot poison the cache) and what it drops when a cached copy fails it.
//
// A path of no tile layer ("dataset.json", anything else) passes: only tiles are checked.

#include <cstdint>
#include <functional>
#include <span>
#include <string>

#include "core/result.h"
#include "datasets/dataset_format.h"

namespace vegstream::streaming {

// OK when `bytes` are the tile `relativePath` names, whole and decodable as the dataset says,
// else why not. Thread-safe.
using TileCheck = std::function<Status(const std::string& relativePath, std::span<const uint8_t> bytes)>;

// The check for `meta`'s tiles; errors are InvalidInput naming `sourceName`/path and the problem.
TileCheck tileCheckFor(const datasets::DatasetMeta& meta, const std::string& sourceName);

}  // namespace vegstream::streaming
