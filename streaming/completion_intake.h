#pragma once
// CompletionIntake (internal to the streamer, tile_streamer.h): the decode pipeline's
// completions → tile states, on the frame thread (README "One frame", step 3). It owns the
// completions settle() has taken from the pipeline but not yet applied.
//
// Contract:
//   - take(): what was held back, then what the pipeline has, in that order (`inRequestOrder`:
//     sorted by request, stably, so a request's Fetched stays before its final completion and a
//     batch is taken in the same order whatever order the workers finished in). A completion of
//     a request no longer in flight (cancelled after the pipeline queued it) is dropped.
//     Fetched → Decoding; Missing → Failed; FetchFailed → FailedTemporarily (Failed when
//     permanent); Cancelled → Unloaded; DecodeFailed → Failed; Decoded → admitted
//     (tile_residency.h). A final completion ends its request (request_scheduler.h).
//   - awaitInFlight(): settle()'s wait, until every request in flight has its final completion
//     held back.
// Counts bytesRead, requestsMissing, requestsFailed and requestsCancelled into the frame's figures.

#include <vector>

#include "core/clock.h"
#include "core/log.h"
#include "streaming/decode_pipeline.h"
#include "streaming/tile_key.h"
#include "streaming/tile_streamer.h"
#include "streaming/tile_table.h"

namespace vegstream::streaming::detail {

class RequestScheduler;
class TileResidency;

class CompletionIntake {
 public:
  // Every reference outlives the intake.
  CompletionIntake(DecodePipeline& pipeline, TileTable& table, RequestScheduler& requests, TileResidency& residency,
                   const StreamingOptions& options, StreamingFrameStats& stats, const Logger& log);

  void take(double timeS, bool inRequestOrder = false);
  // False when `deadlineS` (on `clock`) passed first.
  bool awaitInFlight(const Clock& clock, double deadlineS);

 private:
  // A request's final completion `c`, for `key` and its entry `e`.
  void apply(const TileKey& key, Entry& e, Completion& c, double timeS);

  DecodePipeline& pipeline_;
  TileTable& table_;
  RequestScheduler& requests_;
  TileResidency& residency_;
  const StreamingOptions& options_;
  StreamingFrameStats& stats_;
  const Logger& log_;
  std::vector<Completion> heldBack_;
};

}  // namespace vegstream::streaming::detail
