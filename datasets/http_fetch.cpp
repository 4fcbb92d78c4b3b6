// Blocking HTTP(S) GETs with the project's retry policy (http_fetch.h). Range requests:
// RFC 9110 §14.2 (the Range header) and §15.3.7 (206 Partial Content).

#include "datasets/http_fetch.h"

#include <cassert>
#include <chrono>
#include <mutex>
#include <thread>

#include <curl/curl.h>

#include "datasets/http_limits.h"
#include "datasets/http_retry_policy.h"
#include "datasets/message.h"

namespace vegstream::datasets {
namespace {

void initCurlOnce() {
  static std::once_flag once;
  std::call_once(once, [] { curl_global_init(CURL_GLOBAL_DEFAULT); });
}

uint64_t requestKey(const std::string& url, const std::optional<ByteRange>& range) {
  uint64_t h = 1469598103934665603ull;  // FNV-1a: a reproducible jitter per request
  for (const char c : url) h = (h ^ static_cast<unsigned char>(c)) * 1099511628211ull;
  if (range) h = (h ^ range->offset) * 1099511628211ull;
  return h;
}

struct Attempt {
  AttemptEnd end;
  std::string problem;
  CappedBody body;
  std::string redirectUrl;  // a 3xx's resolved Location
};

using SteadyTime = std::chrono::steady_clock::time_point;
constexpr int kMaxRedirects = 5;

double msLeft(SteadyTime deadline) {
  return std::chrono::duration<double, std::milli>(deadline - std::chrono::steady_clock::now()).count();
}

}  // namespace

struct HttpFetcher::Pool {
  std::mutex mutex;
  std::vector<CURL*> idle;
  ~Pool() {
    for (CURL* e : idle) curl_easy_cleanup(e);
  }
  CURL* take() {
    std::lock_guard lock(mutex);
    if (idle.empty()) return curl_easy_init();
    CURL* e = idle.back();
    idle.pop_back();
    return e;
  }
  void give(CURL* e) {
    std::lock_guard lock(mutex);
    idle.push_back(e);
  }
};

HttpFetcher::HttpFetcher(HttpFetchOptions options) : options_(std::move(options)), pool_(std::make_unique<Pool>()) {
  initCurlOnce();
  if (!options_.sleepMs) options_.sleepMs = [](long ms) { std::this_thread::sleep_for(std::chrono::milliseconds(ms)); };
}

HttpFetcher::~HttpFetcher() = default;

namespace {

Attempt attemptOnce(CURL* e, const std::string& url, const std::optional<ByteRange>& range, const HttpFetchOptions& o,
                    SteadyTime deadline) {
  Attempt a;
  a.body.limit = o.maxBodyBytes;
  char errorBuffer[CURL_ERROR_SIZE] = {};
  curl_easy_reset(e);
  curl_easy_setopt(e, CURLOPT_URL, url.c_str());
  curl_easy_setopt(e, CURLOPT_WRITEFUNCTION, appendCappedBody);
  curl_easy_setopt(e, CURLOPT_WRITEDATA, &a.body);
  curl_easy_setopt(e, CURLOPT_ERRORBUFFER, errorBuffer);
  TransferLimits limits;
  limits.maxBodyBytes = o.maxBodyBytes;
  limits.connectTimeoutMs = o.connectTimeoutMs;
  limits.attemptTimeoutMs = attemptTimeoutWithin(o.totalTimeoutMs, msLeft(deadline));
  limits.lowSpeedBytesPerS = o.lowSpeedBytesPerS;
  limits.lowSpeedTimeS = o.lowSpeedTimeS;
  applyTransferLimits(e, limits);
  curl_easy_setopt(e, CURLOPT_TCP_KEEPALIVE, 1L);
  curl_easy_setopt(e, CURLOPT_USERAGENT, "vegstream");
  std::string rangeText;
  if (range) {
    rangeText = concat(range->offset, "-", range->offset + range->length - 1);
    curl_easy_setopt(e, CURLOPT_RANGE, rangeText.c_str());
  }
  a.end.code = curl_easy_perform(e);
  curl_easy_getinfo(e, CURLINFO_RESPONSE_CODE, &a.end.httpStatus);
  curl_off_t length = -1;
  curl_easy_getinfo(e, CURLINFO_CONTENT_LENGTH_DOWNLOAD_T, &length);
  a.end.contentLength = length;
  a.end.bodyBytes = a.body.bytes.size();
  a.end.bodyExceeded = a.body.exceeded;
  a.end.bodyCap = o.maxBodyBytes;
  const char* type = nullptr;
  if (curl_easy_getinfo(e, CURLINFO_CONTENT_TYPE, &type) == CURLE_OK && type != nullptr) a.end.contentType = type;
  a.end.binaryExpected = true;  // tiles and archives: never a document
  const char* location = nullptr;
  if (curl_easy_getinfo(e, CURLINFO_REDIRECT_URL, &location) == CURLE_OK && location != nullptr)
    a.redirectUrl = location;
  if (a.end.code == CURLE_FILESIZE_EXCEEDED)
    a.problem = concat("the announced body exceeds ", o.maxBodyBytes, " bytes");
  else
    a.problem = describeAttempt(a.end, errorBuffer);
  return a;
}

}  // namespace

Result<std::optional<std::vector<uint8_t>>> HttpFetcher::get(const std::string& url,
                                                             std::optional<ByteRange> range) const {
  assert(!range || range->length > 0);
  const std::string what =
      range ? concat("GET ", url, " (bytes ", range->offset, "-", range->offset + range->length - 1, ")")
            : concat("GET ", url);
  CURL* e = pool_->take();
  if (e == nullptr) return makeError(ErrorKind::Io, concat(what, ": libcurl could not make a handle"));
  const SteadyTime deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(options_.requestDeadlineMs);
  auto failed = [&](const std::string& problem, int attempts) {
    curl_easy_cleanup(e);  // a handle whose connection went wrong is not kept
    return makeError(ErrorKind::InvalidInput,
                     concat(what, ": ", problem, " (", attempts, attempts == 1 ? " attempt)" : " attempts)"));
  };
  std::string target = url;
  int redirects = 0;
  for (int attempt = 1;; ++attempt) {
    Attempt a = attemptOnce(e, target, range, options_, deadline);
    if (a.end.code == CURLE_OK && isRedirectStatus(a.end.httpStatus)) {
      auto next = redirectTarget(target, a.redirectUrl, options_.allowRedirects);
      if (!next) return failed(next.error().message, attempt);
      if (++redirects > kMaxRedirects) return failed(concat("more than ", kMaxRedirects, " redirects"), attempt);
      target = *next;
      --attempt;  // a redirect is not a failed attempt
      continue;
    }
    const AttemptVerdict verdict = judgeAttempt(a.end);
    if (verdict == AttemptVerdict::Ok) {
      pool_->give(e);
      if (range && a.end.httpStatus != 206)
        return makeError(ErrorKind::InvalidInput, concat(what, ": HTTP ", a.end.httpStatus,
                                                         " instead of 206: the server does not serve byte "
                                                         "ranges, which a PMTiles archive over HTTP needs"));
      if (range && a.body.bytes.size() > range->length)
        return makeError(ErrorKind::InvalidInput,
                         concat(what, ": ", a.body.bytes.size(), " bytes for a range of ", range->length));
      return std::optional<std::vector<uint8_t>>(std::move(a.body.bytes));
    }
    if (verdict == AttemptVerdict::Missing) {
      pool_->give(e);
      return std::optional<std::vector<uint8_t>>();
    }
    if (verdict == AttemptVerdict::Fail || attempt >= options_.maxAttempts) return failed(a.problem, attempt);
    const long delay =
        backoffDelayMs(attempt + 1, requestKey(url, range), options_.backoffBaseMs, options_.backoffMaxMs);
    if (msLeft(deadline) < static_cast<double>(delay) + 1.0)
      return failed(concat(a.problem, "; the request's deadline of ", options_.requestDeadlineMs, " ms passed"),
                    attempt);
    options_.sleepMs(delay);
  }
}

}  // namespace vegstream::datasets
