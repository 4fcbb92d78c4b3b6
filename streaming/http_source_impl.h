#pragma once
// Private to streaming/: HttpTileSource's implementation (http_tile_source.h), shared by
// http_tile_source.cpp (creation, the callers' side) and http_io_loop.cpp (the I/O task).
//
// Threads: callers of start()/cancel()/readText() append Commands under `mutex` and wake the
// I/O task; everything curl-related and every Transfer is touched by the I/O task only (or by
// the destructor when the runner never started the task).
// `mutex` also guards the counters and the set of live request ids, which any thread may read.

#include "streaming/http_tile_source.h"

#include <cassert>
#include <condition_variable>
#include <map>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include <curl/curl.h>

#include "datasets/http_retry_policy.h"
#include "streaming/disk_tile_cache.h"
#include "streaming/http_transfer.h"

namespace vegstream::streaming {
namespace http_source {

// What a caller asks the I/O task.
struct Command {
  std::unique_ptr<detail::Transfer> start;  // null: cancel `cancelId`
  RequestId cancelId = 0;
};

}  // namespace http_source

struct HttpTileSource::Impl {
  using AttemptEnd = datasets::AttemptEnd;
  using Command = http_source::Command;
  using Transfer = detail::Transfer;

  enum class Loop { NotStarted, Running, Done };
  HttpSourceOptions opt;
  SteadyClock ownClock;
  const Clock* clock = &ownClock;
  std::string base;  // baseUrl ending in '/'
  std::unique_ptr<DiskTileCache> cache;
  Logger log;
  CURLM* multi = nullptr;

  // Shared with callers, under `mutex`.
  mutable std::mutex mutex;
  std::vector<Command> commands;
  bool stopping = false;
  uint64_t nextSeq = 0;
  std::unordered_set<RequestId> live;  // started tiles not yet called back
  SourceCounters counters;
  HttpTransportStats transport;
  std::shared_ptr<const TileCheck> tileCheck;  // null: none set

  // I/O thread only.
  std::map<uint64_t, std::unique_ptr<Transfer>> transfers;  // by seq: queued, backing off, running
  std::unordered_map<RequestId, uint64_t> seqOfTile;
  size_t running = 0;
  Loop loop = Loop::NotStarted;  // under `mutex`
  std::condition_variable loopDone;

  // The I/O task, or the destructor when the task never started: runs run() once.
  void runOnce() {
    {
      std::lock_guard lock(mutex);
      if (loop != Loop::NotStarted) return;
      loop = Loop::Running;
    }
    run();
    std::lock_guard lock(mutex);
    loop = Loop::Done;
    loopDone.notify_all();
  }

  // Queues a command for the I/O thread and wakes it. A tile start also becomes live and
  // counted in the same critical section, so a cancel() after start() always follows it.
  void post(Command c) {
    {
      std::lock_guard lock(mutex);
      if (c.start) {
        c.start->seq = nextSeq++;
        if (c.start->isTile) {
          const bool fresh = live.insert(c.start->id).second;
          assert(fresh && "start() with the id of a request still in flight");
          (void)fresh;
          ++counters.requestsStarted;
        }
      }
      commands.push_back(std::move(c));
    }
    curl_multi_wakeup(multi);
  }

  void run();
  bool takeCommands();
  void accept(std::unique_ptr<Transfer> t);
  void launchReady(double nowS);
  void launch(Transfer& t);
  void drainFinished();
  void endAttempt(Transfer& t, CURLcode code);
  bool followRedirect(Transfer& t, const AttemptEnd& end);
  Status checkTile(const Transfer& t, std::span<const uint8_t> bytes);
  void retryOrFail(Transfer& t);
  void stopRunning(Transfer& t);
  void complete(uint64_t seq, FetchOutcome outcome, std::string message);
  long pollTimeoutMs(double nowS) const;
};

}  // namespace vegstream::streaming
