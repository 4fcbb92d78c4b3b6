// The limits of one HTTP transfer (http_limits.h).

#include "datasets/http_limits.h"

#include <algorithm>
#include <cctype>
#include <cmath>

namespace vegstream::datasets {
namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

struct UrlParts {
  std::string scheme, host, port;
};

// Scheme, host and port (the scheme's default when absent; host and port empty for a URL
// without a host, "file:///…") of an absolute URL; false when it does not parse.
bool partsOf(const std::string& url, UrlParts& out) {
  CURLU* u = curl_url();
  if (u == nullptr) return false;
  const unsigned flags = CURLU_NON_SUPPORT_SCHEME;
  bool ok = curl_url_set(u, CURLUPART_URL, url.c_str(), flags) == CURLUE_OK;
  char* scheme = nullptr;
  char* host = nullptr;
  char* port = nullptr;
  ok = ok && curl_url_get(u, CURLUPART_SCHEME, &scheme, 0) == CURLUE_OK;
  if (ok) {
    curl_url_get(u, CURLUPART_HOST, &host, 0);
    curl_url_get(u, CURLUPART_PORT, &port, CURLU_DEFAULT_PORT);
    out = {lower(scheme), host ? lower(host) : std::string(), port ? port : ""};
  }
  curl_free(scheme);
  curl_free(host);
  curl_free(port);
  curl_url_cleanup(u);
  return ok;
}

}  // namespace

size_t appendCappedBody(char* data, size_t size, size_t count, void* user) {
  auto* b = static_cast<CappedBody*>(user);
  const size_t n = size * count;
  if (b->bytes.size() + n > b->limit) {
    b->exceeded = true;
    return 0;  // aborts the transfer (CURLE_WRITE_ERROR)
  }
  b->bytes.insert(b->bytes.end(), reinterpret_cast<uint8_t*>(data), reinterpret_cast<uint8_t*>(data) + n);
  return n;
}

void applyTransferLimits(CURL* e, const TransferLimits& l) {
  curl_easy_setopt(e, CURLOPT_NOSIGNAL, 1L);
  curl_easy_setopt(e, CURLOPT_CONNECTTIMEOUT_MS, l.connectTimeoutMs);
  curl_easy_setopt(e, CURLOPT_TIMEOUT_MS, l.attemptTimeoutMs);
  curl_easy_setopt(e, CURLOPT_MAXFILESIZE_LARGE, static_cast<curl_off_t>(l.maxBodyBytes));
  if (l.lowSpeedTimeS > 0) {
    curl_easy_setopt(e, CURLOPT_LOW_SPEED_LIMIT, l.lowSpeedBytesPerS);
    curl_easy_setopt(e, CURLOPT_LOW_SPEED_TIME, l.lowSpeedTimeS);
  }
  curl_easy_setopt(e, CURLOPT_FOLLOWLOCATION, 0L);
  curl_easy_setopt(e, CURLOPT_PROTOCOLS_STR, "http,https");
  curl_easy_setopt(e, CURLOPT_REDIR_PROTOCOLS_STR, "http,https");
}

long attemptTimeoutWithin(long attemptTimeoutMs, double leftMs) {
  const double capped = std::min(static_cast<double>(attemptTimeoutMs), std::ceil(leftMs));
  return std::max(1L, static_cast<long>(capped));
}

Result<std::string> redirectTarget(const std::string& fromUrl, const std::string& location, bool anyHost) {
  const std::string head = "redirect from " + fromUrl + " to '" + location.substr(0, 200) + "' refused: ";
  if (location.empty()) return makeError(ErrorKind::InvalidInput, head + "no Location");
  UrlParts from, to;
  if (!partsOf(location, to)) return makeError(ErrorKind::InvalidInput, head + "not a URL");
  if (to.scheme != "http" && to.scheme != "https")
    return makeError(ErrorKind::InvalidInput, head + "only http:// and https:// are followed");
  if (anyHost) return location;
  if (!partsOf(fromUrl, from) || from.host != to.host || from.port != to.port)
    return makeError(ErrorKind::InvalidInput, head + "another host (--allow-redirects follows it)");
  return location;
}

bool textualContentType(const std::string& contentType) {
  const std::string t = lower(contentType.substr(0, contentType.find(';')));
  if (t.rfind("text/", 0) == 0) return true;
  const auto endsWith = [&](const std::string& tail) {
    return t.size() >= tail.size() && t.compare(t.size() - tail.size(), tail.size(), tail) == 0;
  };
  return endsWith("/json") || endsWith("+json") || endsWith("/xml") || endsWith("+xml");
}

}  // namespace vegstream::datasets
