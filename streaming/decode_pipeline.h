#pragma once
// DecodePipeline (internal to the streamer): where fetched bytes become tiles, off the frame
// thread. The source's callbacks hand their results in (onFetched); Ok results queue a decode
// job for the decode threads; every outcome and every decoded tile becomes a Completion that the
// frame thread takes in update() (takeCompletions). Nothing here knows tile states: the frame
// thread owns them.
//
// Cancellation: cancel(id) makes sure nothing more about the request is ever reported — a queued
// decode job or a pending completion is removed at once; a fetch still at the source or a decode
// in progress is marked, and its result dropped when it arrives. So a cancelled request can
// never become resident.
//
// Lifetime: held through shared_ptr by the streamer and by every callback given to the source,
// so a callback that arrives after the streamer is gone finds it alive; stop() (the streamer's
// destructor) joins the decode threads, and results arriving later are dropped.

#include <condition_variable>
#include <chrono>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <unordered_set>
#include <vector>

#include "datasets/tile_codec.h"
#include "streaming/tile_key.h"
#include "streaming/tile_source.h"
#include "streaming/tile_streamer.h"

namespace vegstream::streaming::detail {

struct Completion {
  enum class Kind {
    Fetched,       // the bytes arrived (a decode job is queued): Requested → Decoding
    Missing,       // final
    FetchFailed,   // final for this request (the tile may be asked again later)
    Cancelled,     // the source cancelled it on its own (e.g. while shutting down)
    Decoded,       // final: heights or colors set
    DecodeFailed,  // final: corrupt bytes
  };
  Kind kind = Kind::Fetched;
  RequestId id = 0;
  uint64_t bytes = 0;    // Fetched: payload size
  int attempts = 0;      // fetch attempts the source made
  std::string message;   // Missing / FetchFailed / DecodeFailed: why, naming the file
  std::shared_ptr<const datasets::HeightTile> heights;
  std::shared_ptr<const datasets::ColorTile> colors;
  std::shared_ptr<const TileExtra> extra;
};

class DecodePipeline {
 public:
  DecodePipeline(datasets::ElevationEncoding encoding, int decodeThreads, HeightExtraFn heightExtra = {});
  ~DecodePipeline();  // stop() must have been called (asserted)
  DecodePipeline(const DecodePipeline&) = delete;
  DecodePipeline& operator=(const DecodePipeline&) = delete;

  // Any thread (the source's): the result of request `id` for `key`; `name` names it in errors.
  void onFetched(const TileKey& key, const std::string& name, FetchResult&& result);

  // Frame thread.
  void cancel(RequestId id);
  std::vector<Completion> takeCompletions();
  // Waits until a completion is pending or `timeout` passes; true when one is pending.
  bool waitForCompletions(std::chrono::duration<double> timeout);
  std::size_t decodesQueued() const;
  // Joins the decode threads; everything reported afterwards is dropped. Idempotent.
  void stop();

 private:
  struct Job {
    RequestId id = 0;
    TileKey key;
    std::string name;
    std::vector<uint8_t> bytes;
  };
  void runWorker();
  Completion decode(Job& job) const;
  void pushLocked(Completion&& c);

  const datasets::ElevationEncoding encoding_;
  const HeightExtraFn heightExtra_;
  mutable std::mutex mu_;
  std::condition_variable jobsCv_;         // decode threads wait here
  std::condition_variable completionsCv_;  // settle() waits here
  std::deque<Job> jobs_;
  std::vector<Completion> completions_;
  std::unordered_set<RequestId> cancelled_;  // at the source or being decoded: drop on arrival
  std::unordered_set<RequestId> decoding_;   // being decoded right now
  bool closed_ = false;
  std::vector<std::thread> workers_;
};

}  // namespace vegstream::streaming::detail
