#pragma once
// A JSON value from user data as message text, without echoing unbounded input and without
// recursion: a string or number as at most its first 80 characters (control characters
// escaped, printable.h), a container as its type ("an object of 3 members", "an array of 2
// values"). Never a recursive dump(): a value nested 100 000 deep would overflow the stack.
// Also jsonDepthAtMost, an iterative depth check to run before anything recursive (a dump, a
// recursive walk) touches user JSON.
//
// Templates on the JSON type (nlohmann::json), so core itself depends on no JSON library.

#include <algorithm>
#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/printable.h"

namespace vegstream {

// nlohmann's exception text without its "[json.exception.parse_error.101] " tag, bounded and
// escaped: its "last read: '…'" quotes the input (a string token can be megabytes long).
inline std::string jsonExceptionText(std::string_view what) {
  if (what.rfind("[json.exception.", 0) == 0)
    if (const auto tag = what.find("] "); tag != std::string_view::npos) what.remove_prefix(tag + 2);
  return printable(what, 2 * kPrintableChars);
}

// A parse error as "line L, column C: what went wrong", L and C (1-based) counted here from the
// error's byte offset (nlohmann's own column is 0 when the token before a line break broke the
// parse), the rest of nlohmann's text bounded and escaped. `byte`: parse_error::byte.
inline std::string jsonParseErrorText(std::string_view text, size_t byte, std::string_view what) {
  const size_t at = std::min(byte > 0 ? byte - 1 : 0, text.size());
  size_t line = 1, column = 1;
  for (size_t i = 0; i < at; ++i) {
    column = text[i] == '\n' ? 1 : column + 1;
    line += text[i] == '\n';
  }
  std::string reason = jsonExceptionText(what);
  if (reason.rfind("parse error", 0) == 0)  // "parse error at line 3, column 0: …": ours instead
    if (const auto colon = reason.find(": "); colon != std::string::npos) reason.erase(0, colon + 2);
  return "line " + std::to_string(line) + ", column " + std::to_string(column) + ": " + reason;
}

template <typename Json>
std::string jsonValueText(const Json& v) {
  if (v.is_string()) return "\"" + printable(v.template get_ref<const std::string&>()) + "\"";
  if (v.is_object()) return "an object of " + std::to_string(v.size()) + " member(s)";
  if (v.is_array()) return "an array of " + std::to_string(v.size()) + " value(s)";
  if (v.is_discarded()) return "an invalid value";
  return printable(v.dump());  // a number, true, false or null: a scalar, never recursive
}

// True when no value inside `v` is nested more than `maxDepth` containers deep (v itself at 1).
template <typename Json>
bool jsonDepthAtMost(const Json& v, size_t maxDepth) {
  std::vector<std::pair<const Json*, size_t>> stack{{&v, 1}};
  while (!stack.empty()) {
    auto [j, depth] = stack.back();
    stack.pop_back();
    if (!j->is_structured()) continue;
    if (depth > maxDepth) return false;
    for (const Json& child : *j) stack.emplace_back(&child, depth + 1);
  }
  return true;
}

}  // namespace vegstream
