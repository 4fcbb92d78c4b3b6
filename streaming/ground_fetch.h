#pragma once
// Fetching a batch of files at once through a tile source, under one deadline: the blocking
// ground loads (dataset_snapshot.h) that must finish before a flight starts. Every file goes
// through TileSource::start(), so the batch gets what tiles get — parallel transfers up to the
// source's limit, retries with back-off, per-request deadlines, caps, the disk cache — instead
// of one blocking read after another.

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "streaming/tile_source.h"

namespace vegstream::streaming {

struct BatchFetchOptions {
  long deadlineMs = 60'000;  // the whole batch: what is still unanswered then is given up
};

// Starts all `paths` and hands each result to take(index into paths, result) on the calling
// thread, as results arrive (so at most the source's transfers and the results not yet taken
// are in memory at once). Requests still unanswered at the deadline are cancelled and handed
// over as Failed, their message saying the deadline passed. Returns once every path is handed
// over, each exactly once. Request ids are drawn from a range of their own, apart from the
// streamer's.
void fetchBatch(TileSource& source, const std::vector<std::string>& paths, const BatchFetchOptions& options,
                const std::function<void(size_t, FetchResult&&)>& take);

}  // namespace vegstream::streaming
