#pragma once
// One request of the HTTP tile source (http_tile_source.h) across its attempts, and what one
// attempt sets up on and reads back from its libcurl easy handle. Internal to the source: only
// its I/O task touches a Transfer.

#include <cstdint>
#include <optional>
#include <string>

#include <curl/curl.h>

#include "datasets/http_limits.h"
#include "datasets/http_retry_policy.h"
#include "streaming/http_tile_source.h"

namespace vegstream::streaming::detail {

// One request from start() to its callback, across all its attempts.
struct Transfer {
  uint64_t seq = 0;  // start order: queued transfers launch in this order
  RequestId id = 0;
  bool isTile = true;  // start()ed (counted, cancellable, cached) or readText()'s
  std::string requestUrl;  // as asked: names the request in messages, its host bounds redirects
  std::string url;         // where the next attempt goes (requestUrl, or a redirect's target)
  std::string cacheKey;    // requestUrl without its scheme
  std::string path;        // relative to the dataset root (the tile check's argument)
  FetchCallback done;
  int attempts = 0;
  int redirects = 0;
  double notBeforeS = 0.0;  // back-off: not launched again before this (clock seconds)
  double deadlineS = 0.0;   // set at the first launch: the request fails once past it
  CURL* easy = nullptr;     // non-null while running
  datasets::CappedBody body;
  char errorBuffer[CURL_ERROR_SIZE] = {};
  std::string lastProblem;
};

// Sets `e` up for the next attempt of `t` (its URL, the capped body, the limits of
// datasets/http_limits.h with the attempt's time-out cut to t's deadline), and resets t's body.
void configureAttempt(CURL* e, Transfer& t, const HttpSourceOptions& o, double nowS);

// How the attempt on t.easy ended (status, lengths, content type, whether the body passed the
// cap); sets t.lastProblem to its one-line description.
datasets::AttemptEnd readAttemptEnd(Transfer& t, CURLcode code, uint64_t maxBodyBytes);

// After a 3xx on t.easy: the URL to go on at (http(s) only; t.requestUrl's host only unless
// `anyHost`), or nullopt with t.lastProblem saying why not (also past `maxRedirects`).
std::optional<std::string> redirectHop(Transfer& t, long httpStatus, bool anyHost, int maxRedirects);

}  // namespace vegstream::streaming::detail
