#pragma once
// What an HTTP fetch does with the end of one attempt: accept it, report the file missing, try
// again after a back-off, or give up. Pure functions, so the policy is tested apart from any
// network; the streamer's HTTP source (streaming/http_tile_source) and the importer's URL
// fetches (datasets/http_fetch) only apply it. It lives in datasets/ because both use it and
// streaming/ sits above datasets/ (DESIGN.md, "Folders").
//
// Retried (up to maxAttempts): 5xx, 408 and 429, time-outs and stalls, connection failures and
// resets, bodies shorter than announced (CURLE_PARTIAL_FILE, or a Content-Length mismatch), a
// 2xx whose Content-Type says it is a document (an HTML error page from a proxy) where a tile
// was asked for, and any other transport error that a second connection may not repeat.
// Never retried: 404 and 410 (→ Missing: the file is not there, asking again will not change
// that), other 4xx (→ Failed: the request itself is wrong), and errors of this machine's own
// set-up (bad URL, unsupported protocol, out of memory), a body over the size cap (announced or
// received: http_limits.h), and too many redirects.

#include <cstdint>
#include <string>

#include <curl/curl.h>

namespace vegstream::datasets {

enum class AttemptVerdict { Ok, Missing, Retry, Fail };

struct AttemptEnd {
  CURLcode code = CURLE_OK;
  long httpStatus = 0;         // 0 when no response arrived
  int64_t contentLength = -1;  // announced by the server, -1 when not announced
  uint64_t bodyBytes = 0;      // what arrived
  bool bodyExceeded = false;   // the received body passed the cap (CappedBody::exceeded) …
  uint64_t bodyCap = 0;        // … of this many bytes
  std::string contentType;     // as announced; empty when not
  bool binaryExpected = false; // a tile or archive was asked for: a textual Content-Type is wrong
};

AttemptVerdict judgeAttempt(const AttemptEnd& end);

// One line for FetchResult::message and the log: "HTTP 503", "timed out after …", …
std::string describeAttempt(const AttemptEnd& end, const char* curlErrorBuffer);

// Delay before attempt `nextAttempt` (2, 3, …): base·2^(nextAttempt−2), capped at maxMs, then
// scaled by a jitter factor in [0.5, 1.0] drawn from (requestKey, nextAttempt), so that many
// tiles failing together do not come back together, and a run is still reproducible.
long backoffDelayMs(int nextAttempt, uint64_t requestKey, long baseMs, long maxMs);

}  // namespace vegstream::datasets
