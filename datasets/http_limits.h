#pragma once
// What one HTTP transfer may cost, and where it may lead: the limits that both HTTP clients of
// the project (streaming/http_tile_source, the streamer's tiles; datasets/http_fetch, the
// importer's URL sources) put on every libcurl easy handle, so a hostile or broken server can
// neither fill memory, nor hold a request for ever, nor send it somewhere else.
//
//   body size   the announced Content-Length (CURLOPT_MAXFILESIZE_LARGE) AND the bytes that
//               actually arrive (CappedBody: the write callback aborts once past the cap; a body
//               without Content-Length, or one longer than announced, stops there)
//   stalls      an attempt slower than lowSpeedBytesPerS for lowSpeedTimeS is aborted
//               (CURLOPT_LOW_SPEED_*: a server that stops answering, or trickles bytes)
//   time        connect time-out and a time-out of the whole attempt (CURLOPT_TIMEOUT_MS); the
//               callers add a deadline over all attempts of one request
//   protocols   http and https only (CURLOPT_PROTOCOLS_STR, CURLOPT_REDIR_PROTOCOLS_STR)
//   redirects   never followed by libcurl (CURLOPT_FOLLOWLOCATION off): the caller reads
//               CURLINFO_REDIRECT_URL and asks redirectTarget() whether to follow — only to
//               http(s), and only to the same host unless the user passed --allow-redirects.

#include <cstdint>
#include <string>
#include <vector>

#include <curl/curl.h>

#include "core/result.h"

namespace vegstream::datasets {

struct TransferLimits {
  uint64_t maxBodyBytes = 16ull << 20;  // announced or received, whichever comes first
  long connectTimeoutMs = 5'000;
  long attemptTimeoutMs = 20'000;  // one attempt, connect included
  long lowSpeedBytesPerS = 1'024;  // slower than this …
  long lowSpeedTimeS = 5;          // … for this long: the attempt is aborted (0: no check)
};

// A body that stops growing at `limit` bytes: the write callback returns 0 past it, which makes
// libcurl abort the transfer with CURLE_WRITE_ERROR; `exceeded` tells that case apart.
struct CappedBody {
  std::vector<uint8_t> bytes;
  uint64_t limit = 0;
  bool exceeded = false;
  void clear() {
    bytes.clear();
    exceeded = false;
  }
};
// CURLOPT_WRITEFUNCTION with a CappedBody* as CURLOPT_WRITEDATA.
size_t appendCappedBody(char* data, size_t size, size_t count, void* user);

// Sets the limits above on `e`, and: no automatic redirects, http(s) only, no signals.
void applyTransferLimits(CURL* e, const TransferLimits& limits);

// `attemptTimeoutMs`, shortened so that the attempt ends by a request's deadline `leftMs` away
// (never below 1 ms: libcurl reads 0 as "no time-out").
long attemptTimeoutWithin(long attemptTimeoutMs, double leftMs);

// The absolute URL to follow after a 3xx from `fromUrl` whose Location resolved to `location`
// (CURLINFO_REDIRECT_URL), or InvalidInput saying why not: empty location, a scheme other than
// http or https ("file://", "ftp://" …), or — unless `anyHost` — a host or port other than
// fromUrl's. The message is one line naming both URLs.
Result<std::string> redirectTarget(const std::string& fromUrl, const std::string& location, bool anyHost);

constexpr bool isRedirectStatus(long status) {
  return status == 301 || status == 302 || status == 303 || status == 307 || status == 308;
}

// True for a Content-Type no tile or archive is sent as: text/* (an HTML error page, plain
// text), and JSON or XML documents. Empty (not announced) is not textual.
bool textualContentType(const std::string& contentType);

}  // namespace vegstream::datasets
