#pragma once
// HttpTileSource: a dataset directory served over HTTP(S) by any static server (nginx, a CDN,
// object storage), read through libcurl.
//
// One long-running task (TaskRunner::postLongRunning: a thread the runner owns) drives one
// libcurl multi handle: connections are kept alive and reused
// between tiles (HTTP/1.1 keep-alive; HTTP/2 multiplexing where a TLS server offers it), DNS
// answers are cached. start() and cancel() only queue a command and wake the thread
// (curl_multi_wakeup); they never block on I/O.
//
// Policy (datasets/http_retry_policy.h): at most maxInFlight transfers at once, the rest wait in start
// order; each attempt has a connect and a total time-out; 5xx, time-outs, connection errors
// and truncated bodies are retried after an exponential back-off with jitter, up to
// maxAttempts tries in all; 404/410 end as Missing and other 4xx as Failed at once.
//
// Limits (datasets/http_limits.h): a body is capped as announced and as received (maxBodyBytes),
// an attempt that stalls or trickles is aborted (low-speed limit) and retried, each attempt
// has a time-out and each request a deadline over all its attempts and back-offs (counted from
// its first launch, not from start(): queued requests do not use it up). Redirects are followed
// by hand, at most 5, to http(s) only, and to the base URL's host only unless allowRedirects.
// A tile image (.png, .jpg, .webp) answered 2xx with a textual Content-Type (an HTML error page)
// is retried, then Failed.
//
// With a cache directory, Ok tiles are also written to a DiskTileCache — only once they pass the
// tile check (setTileCheck; the scene always sets one, streaming/tile_check.h; without one only
// the transport checks above guard the cache) — and a start() whose file is cached
// is answered from it (FetchResult::fromCache) without touching the network, after the same
// check: a cached copy that fails it is removed and the tile fetched again. A network answer that
// fails the check is retried like a truncated body, then Failed: it is never cached.
// readText() never uses the cache: dataset.json is always read fresh.
//
// Callbacks run on the I/O task, exactly once per start(). The destructor cancels what is
// still queued or running (those callbacks run with Cancelled) and waits for the I/O task to
// return (or, if the runner never started it, runs its shutdown itself). Back-off delays are
// measured on the injected clock (tests use a ManualClock and wake(); libcurl's own time-outs
// are real time).
// Counters count start()ed requests only; readText() is not a tile request and is not counted.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "core/clock.h"
#include "core/log.h"
#include "core/task_runner.h"
#include "streaming/http_url.h"  // checkHttpUrl
#include "streaming/tile_check.h"
#include "streaming/tile_source.h"

namespace vegstream::streaming {

struct HttpSourceOptions {
  std::string baseUrl;                            // the dataset root: "https://tiles.example.org/zion" ('/' optional)
  int maxInFlight = 8;                            // transfers running at once (≥ 1)
  long connectTimeoutMs = 5000;                   // per attempt
  long totalTimeoutMs = 20000;                    // per attempt, connect included
  long requestDeadlineMs = 30000;                 // all attempts and back-offs of one request
  long lowSpeedBytesPerS = 1024;                  // an attempt slower than this …
  long lowSpeedTimeS = 5;                         // … for this long is aborted (a stall): retried
  uint64_t maxBodyBytes = 16ull << 20;            // announced or received: no tile is this large
  bool allowRedirects = false;                    // follow redirects to other hosts (http(s) only, always)
  int maxAttempts = 4;                            // tries in all (≥ 1): 1 = no retry
  long backoffBaseMs = 100;                       // delay before the 2nd attempt; doubles each time …
  long backoffMaxMs = 3000;                       // … up to this, then jittered down to half of it at most
  std::optional<std::filesystem::path> cacheDir;  // on-disk tile cache (disk_tile_cache.h)
  uint64_t cacheBudgetBytes = 2ull << 30;
  Logger log;                    // null: nothing is logged
  TaskRunner* tasks = nullptr;   // runs the I/O loop (postLongRunning; it returns only when the
                                 // source goes, so a ManualTaskRunner must not run it); outlives
                                 // the source. Null: a pool of its own
  const Clock* clock = nullptr;  // back-off timing; outlives the source. Null: a steady clock
};

// Transport figures beyond SourceCounters, for tests and reports.
struct HttpTransportStats {
  uint64_t attempts = 0;           // transfers handed to libcurl (tiles and readText)
  uint64_t connectionsOpened = 0;  // new connections libcurl made (CURLINFO_NUM_CONNECTS summed)
};

class HttpTileSource final : public TileSource {
 public:
  // InvalidInput when baseUrl is not an http:// or https:// URL with a host; Io when the
  // cache directory cannot be opened.
  static Result<std::shared_ptr<HttpTileSource>> create(HttpSourceOptions options);

  ~HttpTileSource() override;
  HttpTileSource(const HttpTileSource&) = delete;
  HttpTileSource& operator=(const HttpTileSource&) = delete;

  std::string describe() const override;
  Result<std::string> readText(const std::string& relativePath) override;
  void start(RequestId id, const std::string& relativePath, FetchCallback done) override;
  void cancel(RequestId id) override;
  std::size_t inFlight() const override;
  SourceCounters counters() const override;
  // What the disk cache keeps from now on (see above); any thread. Null: transport checks only.
  void setTileCheck(TileCheck check);

  HttpTransportStats transportStats() const;
  // The URL a relative path is fetched from (characters outside RFC 3986's unreserved set and
  // '/' are percent-encoded).
  std::string urlFor(const std::string& relativePath) const;
  // Makes the I/O task look at its back-offs again now (after a test moved a ManualClock).
  void wake();

 private:
  struct Impl;
  explicit HttpTileSource(std::shared_ptr<Impl> impl, std::unique_ptr<ThreadPool> ownPool);
  std::unique_ptr<ThreadPool> ownPool_;  // only without an injected runner; outlives impl_'s loop
  std::shared_ptr<Impl> impl_;           // shared with the I/O task
};

}  // namespace vegstream::streaming
