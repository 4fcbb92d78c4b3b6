#pragma once
// DecodePipeline (internal to the streamer): where fetched bytes become tiles, off the frame
// thread. The source's callbacks hand their results in (onFetched); Ok results queue a decode
// job for the decode tasks; every outcome and every decoded tile becomes a Completion that the
// frame thread takes in update() (takeCompletions). Nothing here knows tile states: the frame
// thread owns them.
//
// Cancellation: cancel(id) makes sure nothing more about the request is ever reported — a queued
// decode job or a pending completion is removed at once; a fetch still at the source or a decode
// in progress is marked, and its result dropped when it arrives. So a cancelled request can
// never become resident.
//
// Decoding runs as tasks of an injected TaskRunner (core/task_runner.h), at most
// `maxConcurrent` at once: a task takes jobs from the queue until it is empty.
//
// Lifetime: held through shared_ptr by the streamer, by every callback given to the source and
// by every task it posts, so a callback or a task that runs after the streamer is gone finds it
// alive; stop() (the streamer's destructor) waits for decodes under way, and results arriving
// later are dropped. The runner must outlive the streamer (tasks posted before stop() still run
// on it, and return at once).

#include <condition_variable>
#include <chrono>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <unordered_set>
#include <vector>

#include "core/task_runner.h"
#include "datasets/tile_codec.h"
#include "streaming/paired_fetch.h"
#include "streaming/tile_key.h"
#include "streaming/tile_source.h"
#include "streaming/tile_streamer.h"

namespace vegstream::streaming::detail {

struct Completion {
  enum class Kind {
    Fetched,       // the bytes arrived (a decode job is queued): Requested → Decoding
    Missing,       // final
    FetchFailed,   // final for this request (asked again later unless `permanent`)
    Cancelled,     // the source cancelled it on its own (e.g. while shutting down)
    Decoded,       // final: heights or colors set
    DecodeFailed,  // final: corrupt bytes
  };
  Kind kind = Kind::Fetched;
  RequestId id = 0;
  uint64_t bytes = 0;   // Fetched: payload size
  int attempts = 0;     // fetch attempts the source made
  bool permanent = false;  // FetchFailed: never to be asked again (FetchResult::permanent)
  std::string message;  // Missing / FetchFailed / DecodeFailed: why, naming the file
  std::shared_ptr<const datasets::HeightTile> heights;
  std::shared_ptr<const datasets::ColorTile> colors;
  std::shared_ptr<const TileExtra> extra;
};

class DecodePipeline : public std::enable_shared_from_this<DecodePipeline> {
 public:
  // Made through std::make_shared (its tasks hold it). `maxConcurrent` ≥ 1.
  // Every tile is decoded only when its header says `tileSize` pixels a side (dataset.json's
  // tile_size, tile_codec.h): anything else is DecodeFailed, never an over-read downstream.
  DecodePipeline(datasets::ElevationEncoding encoding, int tileSize, TaskRunner& runner, int maxConcurrent,
                 HeightExtraFn heightExtra = {});
  ~DecodePipeline();  // stop() must have been called (asserted)
  DecodePipeline(const DecodePipeline&) = delete;
  DecodePipeline& operator=(const DecodePipeline&) = delete;

  // Any thread (the source's): the result of request `id` for `key`; `name` names it in errors.
  // An imagery tile may come with its companion layers' bytes (paired_fetch.h: NDVI, landcover),
  // decoded into ColorTile::ndvi and ::landcover.
  void onFetched(const TileKey& key, const std::string& name, FetchResult&& result, CompanionBytes companions = {});

  // Frame thread.
  void cancel(RequestId id);
  std::vector<Completion> takeCompletions();
  // Waits until a completion is pending or `timeout` passes; true when one is pending.
  bool waitForCompletions(std::chrono::duration<double> timeout);
  std::size_t decodesQueued() const;
  // Waits for the decodes under way to end; everything reported afterwards is dropped. Idempotent.
  void stop();

 private:
  struct Job {
    RequestId id = 0;
    TileKey key;
    std::string name;
    std::vector<uint8_t> bytes;
    CompanionBytes companions;  // empty bytes: none of that layer
  };
  void drain();  // a decode task: one job, then posted again while jobs are queued
  Completion decode(Job& job) const;
  Status decodeCompanions(const Job& job, datasets::ColorTile& tile) const;
  void pushLocked(Completion&& c);

  const datasets::ElevationEncoding encoding_;
  const int tileSize_;
  const HeightExtraFn heightExtra_;
  mutable std::mutex mu_;
  std::condition_variable completionsCv_;  // settle() waits here
  std::deque<Job> jobs_;
  std::vector<Completion> completions_;
  std::unordered_set<RequestId> cancelled_;  // at the source or being decoded: drop on arrival
  std::unordered_set<RequestId> decoding_;   // being decoded right now
  std::condition_variable idleCv_;           // stop() waits here for decoding_ to empty
  bool closed_ = false;
  TaskRunner& runner_;
  const int maxConcurrent_;
  int tasks_ = 0;  // decode tasks posted and not yet finished
};

}  // namespace vegstream::streaming::detail
