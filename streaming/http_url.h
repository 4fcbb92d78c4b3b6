#pragma once
// URLs of the HTTP tile source: which base URLs it accepts, and how a dataset-relative path
// becomes part of one.

#include <string>

#include "core/result.h"

namespace vegstream::streaming {

// OK when `url` is an http:// or https:// URL with a host, else InvalidInput naming it.
Status checkHttpUrl(const std::string& url);

// `path` with every character outside RFC 3986's unreserved set and '/' percent-encoded.
std::string percentEncodePath(const std::string& path);

}  // namespace vegstream::streaming
