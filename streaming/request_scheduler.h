#pragma once
// RequestScheduler (internal to the streamer, tile_streamer.h): wants → requests. It owns the
// requests in flight (Requested or Decoding, not cancelled: request id → tile) and the request
// ids, and is the only part that starts or cancels fetches at the source.
//
// Contract (README "One frame", steps 2 and 4):
//   - cancelUnwanted(): every request whose tile is no longer wanted is cancelled — the decode
//     pipeline forgets it first, then the source (and its companions' fetches) — so a cancelled
//     tile can never become resident. Called before completions are taken.
//   - schedule(): the wants in order (tile_table.h), Unloaded or FailedTemporarily past the
//     back-off, up to maxRequestsInFlight; a want is requested only if its estimated bytes fit
//     the CPU budget beside what it may not evict (a current want beside the current wants
//     resident or under way, a look-ahead want beside all wants); a current want that does not
//     fit sets wantsExceedCpuBudget. At the limit a current want cancels the lowest-priority
//     look-ahead request. Settling, a current want that failed is asked again at once, up to
//     kSettleFailures in a row.
//   - A request ends when its final completion is taken (completion_intake.h): finish(id).
// Counts requestsIssued, requestsCancelled and retries into the frame's figures.

#include <cstddef>
#include <memory>
#include <optional>
#include <unordered_map>

#include "datasets/dataset_format.h"
#include "streaming/decode_pipeline.h"
#include "streaming/tile_key.h"
#include "streaming/tile_source.h"
#include "streaming/tile_streamer.h"
#include "streaming/tile_table.h"

namespace vegstream::streaming::detail {

// A failed current want counts as settled once it failed this many times in a row.
constexpr int kSettleFailures = 3;

class RequestScheduler {
 public:
  // Every reference outlives the scheduler.
  RequestScheduler(TileTable& table, TileSource& source, std::shared_ptr<DecodePipeline> pipeline,
                   const datasets::DatasetMeta& meta, const StreamingOptions& options, StreamingFrameStats& stats);

  void cancelUnwanted();
  // `settling`: settle()'s rounds (time stands still; see the contract above).
  void schedule(double timeS, bool settling = false);

  // The tile of request `id` while it is in flight; null once it ended or was cancelled.
  const TileKey* keyOf(RequestId id) const;
  // Request `id` has ended (its final completion was taken).
  void finish(RequestId id) { active_.erase(id); }
  std::size_t inFlight() const { return active_.size(); }
  // requestsInFlight (at the source) and decodesQueued (fetched, being decoded).
  void countInFlight(StreamingFrameStats& stats) const;

  // Shutdown (the decode pipeline stopped first): cancels every request still at the source.
  void cancelAtSource();

 private:
  void cancel(RequestId id);
  void issue(const TileKey& key, Entry& e);
  // The look-ahead request of lowest priority, to make room for a current want.
  std::optional<RequestId> weakestLookAheadRequest() const;
  // Bytes the wants will hold once what is in flight lands: {current wants, all wants}.
  std::pair<uint64_t, uint64_t> heldBytes() const;

  TileTable& table_;
  TileSource& source_;
  std::shared_ptr<DecodePipeline> pipeline_;
  const datasets::DatasetMeta& meta_;
  const StreamingOptions& options_;
  StreamingFrameStats& stats_;
  std::unordered_map<RequestId, TileKey> active_;
  RequestId nextRequest_ = 0;
};

}  // namespace vegstream::streaming::detail
