#pragma once
// PairedFetch (internal to the streamer): an imagery tile of a dataset with companion layers
// (datasets/dataset_format.h: NDVI from `import --imagery-nir`, landcover classes from
// `import --landcover`) is one streamer request but several files, imagery/z/x/y, ndvi/z/x/y and
// landcover/z/x/y. They are fetched at once from the same source and joined here, so the tile
// state machine, the budgets and the GPU slots see one imagery tile that carries its companions
// (datasets::ColorTile::ndvi, ::landcover); the decode pipeline decodes them all.
//
// Outcomes: the imagery's own Missing / Failed / Cancelled is the request's (as without
// companions); with imagery Ok, a Missing companion tile is "no such data here" (Ok, no bytes), a
// Failed or Cancelled one fails the request (it is asked again later, like any failed fetch).
//
// Companion c's fetch runs under companionId(id, c), so cancelling a request cancels them all.

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "datasets/dataset_format.h"
#include "streaming/tile_key.h"
#include "streaming/tile_source.h"

namespace vegstream::streaming::detail {

class DecodePipeline;

enum class Companion : uint8_t { Ndvi = 0, Landcover = 1 };
inline constexpr size_t kCompanionCount = 2;

// The companions' files of one imagery tile as they arrived: empty bytes where the layer has no
// tile there (or the dataset no layer); `names` name them in errors.
struct CompanionBytes {
  std::array<std::vector<uint8_t>, kCompanionCount> bytes;
  std::array<std::string, kCompanionCount> names;
  size_t size() const { return bytes[0].size() + bytes[1].size(); }
};

// The source request id of request `id`'s companion `c` (bits 63 and 62: the streamer's own ids
// count up from 1 and never reach them).
inline RequestId companionId(RequestId id, Companion c) {
  return id | (RequestId{1} << (63 - static_cast<int>(c)));
}
inline RequestId requestOfCompanion(RequestId id) { return id & ~(RequestId{3} << 62); }

// The companion layers `meta` has, with their files' dataset-relative paths for tile `id`.
struct CompanionFile {
  Companion kind = Companion::Ndvi;
  std::string path;
};
std::vector<CompanionFile> companionsOf(const datasets::DatasetMeta& meta, const geo::TileId& id);
// Cancels at `source` the companion fetches of imagery request `id` (a no-op for a dataset without).
void cancelCompanions(TileSource& source, const datasets::DatasetMeta& meta, RequestId id);

// Starts every fetch; the joined result reaches pipeline->onFetched once.
void startPairedFetch(TileSource& source, RequestId id, const TileKey& key, const std::string& imageryPath,
                      std::vector<CompanionFile> companions, const std::shared_ptr<DecodePipeline>& pipeline);

}  // namespace vegstream::streaming::detail
