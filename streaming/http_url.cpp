// URLs of the HTTP tile source (http_url.h).

#include "streaming/http_url.h"

#include <mutex>

#include <curl/curl.h>

#include "streaming/escaped_bytes.h"

namespace vegstream::streaming {

std::string percentEncodePath(const std::string& path) {
  return escapeBytes(path, '%', [](char c) {
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' || c == '.' ||
           c == '_' || c == '~' || c == '/';
  });
}

Status checkHttpUrl(const std::string& url) {
  static std::once_flag once;
  std::call_once(once, [] { curl_global_init(CURL_GLOBAL_DEFAULT); });
  CURLU* u = curl_url();
  const CURLUcode rc = curl_url_set(u, CURLUPART_URL, url.c_str(), 0);
  char* scheme = nullptr;
  char* host = nullptr;
  bool good = rc == CURLUE_OK && curl_url_get(u, CURLUPART_SCHEME, &scheme, 0) == CURLUE_OK &&
              curl_url_get(u, CURLUPART_HOST, &host, 0) == CURLUE_OK;
  if (good) good = (std::string(scheme) == "http" || std::string(scheme) == "https") && host[0] != '\0';
  curl_free(scheme);
  curl_free(host);
  curl_url_cleanup(u);
  if (!good) return makeError(ErrorKind::InvalidInput, "'" + url + "' is not an http:// or https:// URL with a host");
  return {};
}

}  // namespace vegstream::streaming
