#pragma once
// HttpFetcher: blocking HTTP(S) GETs for the importer's URL sources (XYZ URL templates, PMTiles
// by URL), whole files or one byte range (RFC 9110 §14, "Range Requests"), through libcurl.
//
// Policy: datasets/http_retry_policy.h, the same rules as the streamer's HTTP source — 5xx,
// 408, 429, time-outs, resets and short bodies are retried after an exponential back-off with
// jitter, up to maxAttempts tries; 404 and 410 end as "no file there" (nullopt) at once; other
// answers fail at once. A range request must be answered 206 with the bytes asked for (or
// fewer, at the end of the file): a server that answers 200 with the whole file is refused,
// since every tile would download the whole archive.
//
// Limits (http_limits.h): the body is capped both as announced and as received, a stalled or
// trickling attempt is aborted (low-speed limit), each attempt has a time-out and the request a
// deadline over all its attempts and back-offs. Redirects are followed by hand, at most 5, only
// to http(s) and only to the same host unless allowRedirects.
//
// Thread-safe: any number of importer workers call get() at once; each call borrows an easy
// handle from a small pool, so connections are kept alive between calls. The back-off waits
// through `sleepMs` (injected; default: the calling thread sleeps) — a batch import has nothing
// else to do meanwhile.

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/result.h"

namespace vegstream::datasets {

struct HttpFetchOptions {
  int maxAttempts = 4;
  long connectTimeoutMs = 10'000;
  long totalTimeoutMs = 120'000;     // one attempt
  long requestDeadlineMs = 300'000;  // all attempts and back-offs of one get()
  long lowSpeedBytesPerS = 1'024;    // an attempt slower than this …
  long lowSpeedTimeS = 10;           // … for this long is aborted and retried
  long backoffBaseMs = 250;
  long backoffMaxMs = 4'000;
  uint64_t maxBodyBytes = 256ull << 20;  // no tile or directory is this large: refused (announced or received)
  bool allowRedirects = false;           // follow redirects to other hosts too (http(s) only, always)
  std::function<void(long ms)> sleepMs;  // null: std::this_thread::sleep_for
};

struct ByteRange {
  uint64_t offset = 0;
  uint64_t length = 0;  // > 0
};

class HttpFetcher {
 public:
  explicit HttpFetcher(HttpFetchOptions options = {});
  ~HttpFetcher();
  HttpFetcher(const HttpFetcher&) = delete;
  HttpFetcher& operator=(const HttpFetcher&) = delete;

  // The body, or nullopt when the server says the file is not there (404, 410). Errors
  // (InvalidInput: the source the user named does not deliver) are one line:
  // "GET URL: HTTP 500 (4 attempts)", "GET URL: Couldn't connect to server: … (4 attempts)".
  Result<std::optional<std::vector<uint8_t>>> get(const std::string& url,
                                                  std::optional<ByteRange> range = std::nullopt) const;

 private:
  struct Pool;
  HttpFetchOptions options_;
  std::unique_ptr<Pool> pool_;
};

}  // namespace vegstream::datasets
