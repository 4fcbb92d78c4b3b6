// The HTTP retry policy (http_retry_policy.h).

#include "datasets/http_retry_policy.h"

#include <algorithm>

#include "datasets/http_limits.h"

namespace vegstream::datasets {

AttemptVerdict judgeAttempt(const AttemptEnd& end) {
  if (end.bodyExceeded) return AttemptVerdict::Fail;  // our own cap: the same server sends it again
  switch (end.code) {
    case CURLE_OK: break;
    // Set-up errors of our own: the same request fails the same way every time.
    case CURLE_UNSUPPORTED_PROTOCOL:
    case CURLE_URL_MALFORMAT:
    case CURLE_NOT_BUILT_IN:
    case CURLE_OUT_OF_MEMORY:
    case CURLE_BAD_FUNCTION_ARGUMENT:
    case CURLE_FILESIZE_EXCEEDED:
    case CURLE_TOO_MANY_REDIRECTS: return AttemptVerdict::Fail;
    // Everything else is transport trouble (resolve, connect, reset, time-out, partial body,
    // TLS hiccup, HTTP/2 stream error) that a fresh attempt may well not meet.
    default: return AttemptVerdict::Retry;
  }
  const long s = end.httpStatus;
  if (s == 404 || s == 410) return AttemptVerdict::Missing;
  if (s == 408 || s == 429 || s >= 500) return AttemptVerdict::Retry;
  if (s < 200 || s >= 300) return AttemptVerdict::Fail;
  // libcurl reports a short body as CURLE_PARTIAL_FILE when it knows the length; check anyway,
  // a truncated tile must never be handed to the decoder as if it were whole.
  if (end.contentLength >= 0 && static_cast<uint64_t>(end.contentLength) != end.bodyBytes) return AttemptVerdict::Retry;
  if (end.binaryExpected && textualContentType(end.contentType)) return AttemptVerdict::Retry;
  return AttemptVerdict::Ok;
}

std::string describeAttempt(const AttemptEnd& end, const char* curlErrorBuffer) {
  if (end.bodyExceeded) return "the body exceeds " + std::to_string(end.bodyCap) + " bytes";
  if (end.code != CURLE_OK) {
    std::string s = curl_easy_strerror(end.code);
    if (curlErrorBuffer != nullptr && curlErrorBuffer[0] != '\0') {
      s += ": ";
      s += curlErrorBuffer;
    }
    return s;
  }
  if (end.contentLength >= 0 && static_cast<uint64_t>(end.contentLength) != end.bodyBytes)
    return "HTTP " + std::to_string(end.httpStatus) + " with " + std::to_string(end.bodyBytes) +
           " bytes of the announced " + std::to_string(end.contentLength);
  if (end.binaryExpected && textualContentType(end.contentType))
    return "HTTP " + std::to_string(end.httpStatus) + " with Content-Type " + end.contentType.substr(0, 80) +
           ", not a tile";
  return "HTTP " + std::to_string(end.httpStatus);
}

long backoffDelayMs(int nextAttempt, uint64_t requestKey, long baseMs, long maxMs) {
  const int doublings = std::clamp(nextAttempt - 2, 0, 30);
  const long raw = std::min(maxMs, baseMs << doublings);
  // SplitMix64 of (key, attempt): a well-mixed, reproducible fraction in [0, 1).
  uint64_t z = requestKey * uint64_t{0x9E3779B97F4A7C15ull} +
               static_cast<uint64_t>(nextAttempt) * uint64_t{0xBF58476D1CE4E5B9ull};
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  const double fraction = static_cast<double>(z >> 11) / static_cast<double>(1ull << 53);
  return static_cast<long>(static_cast<double>(raw) * (0.5 + 0.5 * fraction));
}

}  // namespace vegstream::datasets
