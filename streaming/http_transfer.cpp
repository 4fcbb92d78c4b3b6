// One attempt of the HTTP tile source on its easy handle (http_transfer.h).

#include "streaming/http_transfer.h"

namespace vegstream::streaming::detail {
namespace {

// A tile image by its name ("imagery/12/758/1608.jpg"): a textual answer for it is an error page.
bool isImagePath(const std::string& path) {
  const size_t dot = path.rfind('.');
  if (dot == std::string::npos) return false;
  const std::string ext = path.substr(dot + 1);
  return ext == "png" || ext == "jpg" || ext == "jpeg" || ext == "webp";
}

}  // namespace

void configureAttempt(CURL* e, Transfer& t, const HttpSourceOptions& o, double nowS) {
  t.body.clear();
  t.body.limit = o.maxBodyBytes;
  t.errorBuffer[0] = '\0';
  curl_easy_setopt(e, CURLOPT_URL, t.url.c_str());
  curl_easy_setopt(e, CURLOPT_PRIVATE, &t);
  curl_easy_setopt(e, CURLOPT_WRITEFUNCTION, datasets::appendCappedBody);
  curl_easy_setopt(e, CURLOPT_WRITEDATA, &t.body);
  curl_easy_setopt(e, CURLOPT_ERRORBUFFER, t.errorBuffer);
  datasets::TransferLimits limits;
  limits.maxBodyBytes = o.maxBodyBytes;
  limits.connectTimeoutMs = o.connectTimeoutMs;
  limits.attemptTimeoutMs = datasets::attemptTimeoutWithin(o.totalTimeoutMs, (t.deadlineS - nowS) * 1000.0);
  limits.lowSpeedBytesPerS = o.lowSpeedBytesPerS;
  limits.lowSpeedTimeS = o.lowSpeedTimeS;
  datasets::applyTransferLimits(e, limits);
  curl_easy_setopt(e, CURLOPT_HTTP_VERSION, static_cast<long>(CURL_HTTP_VERSION_2TLS));
  // Over TLS, wait for ALPN to say whether the connection being set up multiplexes (HTTP/2)
  // rather than opening another. Never over plain http: HTTP/1.1 is known only once the first
  // answer arrives, and every other transfer would wait for it.
  if (t.url.rfind("https://", 0) == 0) curl_easy_setopt(e, CURLOPT_PIPEWAIT, 1L);
  curl_easy_setopt(e, CURLOPT_TCP_KEEPALIVE, 1L);
  curl_easy_setopt(e, CURLOPT_USERAGENT, "vegstream");
}

datasets::AttemptEnd readAttemptEnd(Transfer& t, CURLcode code, uint64_t maxBodyBytes) {
  datasets::AttemptEnd end;
  end.code = code;
  curl_easy_getinfo(t.easy, CURLINFO_RESPONSE_CODE, &end.httpStatus);
  curl_off_t length = -1;
  curl_easy_getinfo(t.easy, CURLINFO_CONTENT_LENGTH_DOWNLOAD_T, &length);
  end.contentLength = length;
  end.bodyBytes = t.body.bytes.size();
  end.bodyExceeded = t.body.exceeded;
  end.bodyCap = maxBodyBytes;
  const char* type = nullptr;
  if (curl_easy_getinfo(t.easy, CURLINFO_CONTENT_TYPE, &type) == CURLE_OK && type != nullptr) end.contentType = type;
  end.binaryExpected = t.isTile && isImagePath(t.path);
  t.lastProblem = datasets::describeAttempt(end, t.errorBuffer);
  if (code == CURLE_FILESIZE_EXCEEDED)
    t.lastProblem = "the announced body exceeds " + std::to_string(maxBodyBytes) + " bytes";
  return end;
}

std::optional<std::string> redirectHop(Transfer& t, long httpStatus, bool anyHost, int maxRedirects) {
  const char* location = nullptr;
  curl_easy_getinfo(t.easy, CURLINFO_REDIRECT_URL, &location);
  auto target = datasets::redirectTarget(t.url, location ? location : "", anyHost);
  // Each hop is checked against the host first asked, so a chain cannot walk away from it.
  if (target && !anyHost) target = datasets::redirectTarget(t.requestUrl, *target, false);
  if (!target) {
    t.lastProblem = "HTTP " + std::to_string(httpStatus) + ": " + target.error().message;
    return std::nullopt;
  }
  if (t.redirects >= maxRedirects) {
    t.lastProblem = "more than " + std::to_string(maxRedirects) + " redirects";
    return std::nullopt;
  }
  return *target;
}

}  // namespace vegstream::streaming::detail
