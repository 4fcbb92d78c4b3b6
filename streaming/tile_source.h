#pragma once
// Where tile bytes come from. One interface, two implementations: a dataset directory on disk
// (local_tile_source.h) and a dataset served over HTTP(S) (http_tile_source.h). A source only
// moves bytes; decoding happens on the streamer's workers, never here and never on the frame
// thread.
//
// Paths are relative to the dataset root with '/' separators, exactly the dataset directory's
// layout (DESIGN.md): "dataset.json", "elevation/12/758/1608.png", "imagery/12/758/1608.jpg".

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/result.h"

namespace vegstream::streaming {

using RequestId = uint64_t;

enum class FetchOutcome {
  Ok,         // bytes holds the whole file
  Missing,    // the file does not exist (ENOENT, HTTP 404/410): a fact, never retried
  Failed,     // gave up: retries exhausted or an error that retrying cannot fix
  Cancelled,  // cancel() got there first
};

struct FetchResult {
  RequestId id = 0;
  FetchOutcome outcome = FetchOutcome::Failed;
  std::vector<uint8_t> bytes;
  std::string message;  // why, for Missing / Failed: names the path or URL
  int attempts = 0;     // tries made (1 = no retry)
  bool fromCache = false;
  // Failed for good: a fact about the file that no retry changes (a directory, a FIFO or a
  // device where the tile should be, or a file past the tile ceiling: core/regular_file.h).
  // The streamer then never asks again, as for Missing, but warns once and keeps the reason.
  bool permanent = false;
};

// Called exactly once per started request, with any outcome, on a thread of the source's.
// It must be quick and must not call back into the source.
using FetchCallback = std::function<void(FetchResult&&)>;

struct SourceCounters {
  uint64_t requestsStarted = 0;
  uint64_t requestsCompleted = 0;  // Ok
  uint64_t requestsMissing = 0;
  uint64_t requestsFailed = 0;
  uint64_t requestsCancelled = 0;
  uint64_t retries = 0;
  uint64_t bytesRead = 0;  // payload bytes of Ok results
  uint64_t cacheHits = 0;
};

// Counts one ended request's outcome (and, for Ok, its bytes) into `c`: every source the same way.
inline void countOutcome(SourceCounters& c, FetchOutcome outcome, uint64_t bytes) {
  switch (outcome) {
    case FetchOutcome::Ok:
      ++c.requestsCompleted;
      c.bytesRead += bytes;
      break;
    case FetchOutcome::Missing: ++c.requestsMissing; break;
    case FetchOutcome::Failed: ++c.requestsFailed; break;
    case FetchOutcome::Cancelled: ++c.requestsCancelled; break;
  }
}

class TileSource {
 public:
  virtual ~TileSource() = default;

  // "dir /data/zion" or "https://host/zion": for messages and recordings.
  virtual std::string describe() const = 0;

  // Blocking read of a small file (dataset.json) when a flight opens. Errors name the path or
  // URL; a missing file is NotFound.
  virtual Result<std::string> readText(const std::string& relativePath) = 0;

  // Starts fetching; never blocks on I/O. `done` is called exactly once.
  virtual void start(RequestId id, const std::string& relativePath, FetchCallback done) = 0;

  // Best effort: a request not yet completed ends with Cancelled (its callback still runs).
  virtual void cancel(RequestId id) = 0;

  // Requests started whose callback has not yet returned. Any thread.
  virtual std::size_t inFlight() const = 0;

  virtual SourceCounters counters() const = 0;
};

}  // namespace vegstream::streaming
