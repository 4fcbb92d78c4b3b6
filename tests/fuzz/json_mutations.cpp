// Seeded JSON mutations (json_mutations.h): a scanner finds the value and member spans of the
// valid text, then one to three edits, each chosen by a splitmix64 stream of (seed, index).
// Structural edits (replace a value, delete or duplicate a member) need a valid text to scan, so
// after the text stops being valid JSON only byte-level edits follow.

#include "tests/fuzz/json_mutations.h"

#include <cctype>
#include <cstring>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/fuzz/mutation_rng.h"

namespace vegstream::testing {
namespace {

using Rng = MutationRng;

const std::string& deepArrays() {
  static const std::string s = std::string(400, '[') + std::string(400, ']');
  return s;
}

// Tokens users and broken files put where a value belongs, and stray punctuation.
const std::vector<std::string>& tokens() {
  static const std::vector<std::string> t = {"1e9999",
                                             "-1e9990",
                                             "1e-9999",
                                             "-1e9999",
                                             "1e308",
                                             "-0",
                                             "0",
                                             "1.5",
                                             "-1",
                                             "4096",
                                             "1e30",
                                             "18446744073709551616",
                                             "-9223372036854775809",
                                             "123456789012345678901234567890",
                                             "null",
                                             "true",
                                             "false",
                                             "\"\"",
                                             "\"x\"",
                                             "\"\\u0000\"",
                                             "\"\\ud800\"",
                                             "\"#zzzzzz\"",
                                             "\"\xff\xfe\"",
                                             "[]",
                                             "{}",
                                             "[null]",
                                             "[1e9999]",
                                             "{\"a\":{\"b\":[1,[2,[3]]]}}",
                                             "[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]",
                                             deepArrays(),
                                             "NaN",
                                             "Infinity",
                                             ",",
                                             ":",
                                             "[",
                                             "{",
                                             "]",
                                             "}",
                                             "\"",
                                             "\\",
                                             "/*",
                                             "\"t\":",
                                             "\"lat\": 1e9999,"};
  return t;
}

const std::vector<std::string>& hugeNumbers() {
  static const std::vector<std::string> t = {"1e9999",     "-1e9990",  "-1e9999",
                                             "1e99999999", "[1e9999]", "{\"min\": -1e9990, \"max\": 1e9999}"};
  return t;
}

struct Span {
  size_t begin = 0, end = 0;
};

// Value and member spans of a valid JSON text.
class Scanner {
 public:
  explicit Scanner(const std::string& text) : t_(text) { value(); }
  std::vector<Span> values, members;

 private:
  const std::string& t_;
  size_t i_ = 0;

  char at() const { return i_ < t_.size() ? t_[i_] : '\0'; }
  void ws() {
    while (i_ < t_.size() && std::isspace(static_cast<unsigned char>(t_[i_]))) ++i_;
  }
  void string() {
    ++i_;
    while (i_ < t_.size() && t_[i_] != '"') i_ += t_[i_] == '\\' ? 2 : 1;
    ++i_;
  }
  void value() {
    ws();
    const size_t b = i_;
    const char c = at();
    if (c == '{' || c == '[') {
      const char close = c == '{' ? '}' : ']';
      ++i_;
      ws();
      if (at() == close) {
        ++i_;
      } else {
        while (i_ < t_.size()) {
          ws();
          const size_t kb = i_;
          if (c == '{') {
            string();
            ws();
            ++i_;  // ':'
          }
          value();
          if (c == '{') members.push_back({kb, i_});
          ws();
          const char sep = at();
          ++i_;
          if (sep != ',') break;
        }
      }
    } else if (c == '"') {
      string();
    } else {
      while (i_ < t_.size() && !std::strchr(",]} \t\r\n", t_[i_])) ++i_;
    }
    values.push_back({b, i_});
  }
};

bool isJson(const std::string& text) { return nlohmann::json::accept(text); }

// One edit of `text`; `structural` allows edits that need its spans (text must be valid).
std::string edit(std::string text, Rng& rng, bool structural, bool hugeOnly, std::string& what) {
  const size_t n = text.size();
  const auto& list = hugeOnly ? hugeNumbers() : tokens();
  const std::string& token = list[rng.below(list.size())];
  // Huge numbers only: inserted anywhere, or in place of a value.
  const unsigned kind = hugeOnly ? (rng.below(2) == 0 ? 2u : 4u) : static_cast<unsigned>(rng.below(structural ? 8 : 4));
  switch (structural ? kind : kind % 4) {
    case 0: {  // flip one byte to any other value
      if (n == 0) return text;
      const size_t p = rng.below(n);
      text[p] = static_cast<char>(static_cast<unsigned char>(text[p]) ^ (1 + rng.below(255)));
      what += "flip byte " + std::to_string(p) + "; ";
      return text;
    }
    case 1: {  // cut short
      const size_t len = rng.below(n);
      what += "truncate to " + std::to_string(len) + "; ";
      return text.substr(0, len);
    }
    case 2: {  // a token anywhere
      const size_t p = rng.below(n + 1);
      what += "insert " + token.substr(0, 24) + " at " + std::to_string(p) + "; ";
      return text.insert(p, token);
    }
    case 3: {  // a few bytes gone
      if (n == 0) return text;
      const size_t p = rng.below(n), len = 1 + rng.below(8);
      what += "erase " + std::to_string(len) + " at " + std::to_string(p) + "; ";
      return text.erase(p, len);
    }
    default: break;
  }
  const Scanner scan(text);
  if (scan.values.empty()) return text;
  if (kind == 4 || kind == 6) {  // a value replaced by a token (wrong type, huge number, nesting)
    const Span v = scan.values[rng.below(scan.values.size())];
    what += "replace value at " + std::to_string(v.begin) + " by " + token.substr(0, 24) + "; ";
    return text.replace(v.begin, v.end - v.begin, token);
  }
  if (scan.members.empty()) return text;
  const Span m = scan.members[rng.below(scan.members.size())];
  if (kind == 5) {  // a member deleted (with one comma, so the rest stays valid)
    size_t b = m.begin, e = m.end;
    size_t after = e;
    while (after < n && std::isspace(static_cast<unsigned char>(text[after]))) ++after;
    if (after < n && text[after] == ',') {
      e = after + 1;
    } else {
      size_t before = b;
      while (before > 0 && std::isspace(static_cast<unsigned char>(text[before - 1]))) --before;
      if (before > 0 && text[before - 1] == ',') b = before - 1;
    }
    what += "delete member at " + std::to_string(m.begin) + "; ";
    return text.erase(b, e - b);
  }
  // kind 7: a member duplicated (same key twice), or another member's value put in its place
  if (rng.below(2) == 0) {
    what += "duplicate member at " + std::to_string(m.begin) + "; ";
    return text.insert(m.end, "," + text.substr(m.begin, m.end - m.begin));
  }
  const Span other = scan.values[rng.below(scan.values.size())];
  const std::string replacement = text.substr(other.begin, other.end - other.begin);
  const size_t colon = text.find(':', m.begin);
  if (colon == std::string::npos || colon >= m.end) return text;
  size_t vb = colon + 1;
  while (vb < m.end && std::isspace(static_cast<unsigned char>(text[vb]))) ++vb;
  what += "value of member at " + std::to_string(m.begin) + " from " + std::to_string(other.begin) + "; ";
  return text.replace(vb, m.end - vb, replacement);
}

JsonMutation mutate(const std::string& valid, uint64_t seed, uint64_t index, bool hugeOnly) {
  Rng rng = mutationRng(seed, index);
  JsonMutation m{valid, ""};
  const size_t edits = hugeOnly ? 1 : 1 + rng.below(3);
  bool structural = true;  // the text is valid JSON: its spans can be scanned
  for (size_t e = 0; e < edits; ++e) {
    m.text = edit(std::move(m.text), rng, structural, hugeOnly, m.what);
    structural = e + 1 < edits && isJson(m.text);
  }
  return m;
}

}  // namespace

JsonMutation mutateJson(const std::string& valid, uint64_t seed, uint64_t index) {
  return mutate(valid, seed, index, false);
}

JsonMutation mutateJsonWithHugeNumber(const std::string& valid, uint64_t seed, uint64_t index) {
  return mutate(valid, seed, index, true);
}

}  // namespace vegstream::testing
