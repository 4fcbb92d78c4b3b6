#pragma once
// escapeBytes: text with the bytes a rule refuses written as a marker and two upper-case hex
// digits. Percent-encoding is one ('%', http_url.h), the disk cache's file names another ('_',
// disk_tile_cache.h).

#include <string>
#include <string_view>

namespace vegstream::streaming {

// `text` with every byte c for which keep(c) is false written as `marker` + c's two hex digits.
template <class Keep>
std::string escapeBytes(std::string_view text, char marker, Keep&& keep) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  std::string out;
  for (char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (keep(c)) {
      out += c;
    } else {
      out += marker;
      out += kHex[u >> 4];
      out += kHex[u & 15];
    }
  }
  return out;
}

}  // namespace vegstream::streaming
