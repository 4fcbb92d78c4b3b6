#pragma once
// PairedFetch (internal to the streamer): an imagery tile of a dataset with an NDVI layer
// (datasets/dataset_format.h, `import --imagery-nir`) is one streamer request but two files,
// imagery/z/x/y and ndvi/z/x/y. Both are fetched at once from the same source and joined here,
// so the tile state machine, the budgets and the GPU slots see one imagery tile that carries
// its NDVI (datasets::ColorTile::ndvi); the decode pipeline decodes both.
//
// Outcomes: the imagery's own Missing / Failed / Cancelled is the request's (as without NDVI);
// with imagery Ok, a Missing NDVI tile is "no NDVI here" (Ok, no NDVI bytes), a Failed or
// Cancelled one fails the request (it is asked again later, like any failed fetch).
//
// The NDVI fetch runs under companionId(id), so cancelling a request cancels both.

#include <memory>
#include <string>

#include "streaming/decode_pipeline.h"
#include "streaming/tile_key.h"
#include "streaming/tile_source.h"

namespace vegstream::streaming::detail {

// The source request id of request `id`'s NDVI file (the top bit set: the streamer's own ids
// count up from 1 and never reach it).
inline RequestId companionId(RequestId id) { return id | (RequestId{1} << 63); }

// Starts both fetches; the joined result reaches pipeline->onFetched once.
void startPairedFetch(TileSource& source, RequestId id, const TileKey& key, const std::string& imageryPath,
                      const std::string& ndviPath, const std::shared_ptr<DecodePipeline>& pipeline);

}  // namespace vegstream::streaming::detail
