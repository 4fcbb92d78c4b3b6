// printable (printable.h): escapes control bytes, C1 controls and bytes that are not UTF-8,
// cuts at a byte count (a sequence cut there is escaped byte by byte).

#include "core/printable.h"

namespace vegstream {
namespace {

const char* kHex = "0123456789abcdef";

void hexEscape(std::string& out, unsigned char c) {
  out += "\\x";
  out += kHex[c >> 4];
  out += kHex[c & 15];
}

// Length of the valid UTF-8 sequence at text[i] (2 … 4), or 0 when it is not one.
size_t utf8Length(std::string_view text, size_t i) {
  const auto c = static_cast<unsigned char>(text[i]);
  const size_t n = c >= 0xf0 && c <= 0xf4 ? 4 : c >= 0xe0 && c < 0xf0 ? 3 : c >= 0xc2 && c < 0xe0 ? 2 : 0;
  if (n == 0 || i + n > text.size()) return 0;
  for (size_t k = 1; k < n; ++k)
    if ((static_cast<unsigned char>(text[i + k]) & 0xc0) != 0x80) return 0;
  return n;
}

}  // namespace

std::string printable(std::string_view text, size_t maxChars) {
  const bool cut = text.size() > maxChars;
  const std::string_view shown = cut ? text.substr(0, maxChars) : text;
  std::string out;
  out.reserve(shown.size() + 8);
  for (size_t i = 0; i < shown.size();) {
    const auto c = static_cast<unsigned char>(shown[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
      ++i;
    } else if (c == '\n' || c == '\t' || c == '\r') {
      out += c == '\n' ? "\\n" : c == '\t' ? "\\t" : "\\r";
      ++i;
    } else if (const size_t n = c >= 0x80 ? utf8Length(shown, i) : 0; n > 0) {
      // U+0080 … U+009F (C2 80 … C2 9F) are the C1 controls: escaped like C0.
      if (c == 0xc2 && static_cast<unsigned char>(shown[i + 1]) < 0xa0) {
        const auto b = static_cast<unsigned char>(shown[i + 1]);
        out += "\\u00";
        out += kHex[b >> 4];
        out += kHex[b & 15];
      } else {
        out.append(shown.substr(i, n));
      }
      i += n;
    } else {
      hexEscape(out, c);  // C0 controls, DEL, and bytes that are no UTF-8 (a sequence cut too)
      ++i;
    }
  }
  if (cut) out += "...";
  return out;
}

}  // namespace vegstream
