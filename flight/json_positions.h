#pragma once
// Where each value of a JSON text starts, by field path ("keyframes[3].lat"), so that error
// messages about a field can name its line. nlohmann::json 3.11 keeps no positions in its
// values, so this is a small second pass over text that nlohmann has already accepted:
// it only skips strings, numbers and literals and records each value's byte offset. It also
// notices duplicate keys, which nlohmann silently resolves to the last one.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>

namespace vegstream::flight {

struct LineCol {
  std::size_t line = 1;    // 1-based
  std::size_t column = 1;  // 1-based, in bytes
};

// The line and column of a byte offset (0-based) in text.
LineCol lineColAt(std::string_view text, std::size_t offset);

class JsonPositions {
 public:
  // Paths longer than this (a flight path's are tens of bytes) are not indexed, nor what is under
  // them: indexing them cost time and memory quadratic in the text.
  static constexpr std::size_t kMaxIndexedPath = 512;

  // text must be valid JSON (parse it with nlohmann first); deeper than 64 levels, or under a path
  // longer than kMaxIndexedPath, is not indexed (nor checked for duplicate keys).
  explicit JsonPositions(std::string_view text);

  // Where the value at `path` starts ("" = the root; "a.b[2].c"), if it exists.
  std::optional<LineCol> find(const std::string& path) const;
  // The first key that appears twice in one object, as its field path, if any.
  const std::optional<std::string>& firstDuplicate() const { return duplicate_; }

 private:
  void value(const std::string& path, int depth);
  void skipSpace();
  void skipNested();         // at '{' or '[': past its matching close, unindexed
  std::string readString();  // at '"': returns the raw (unescaped-enough) contents

  std::string_view text_;
  std::size_t pos_ = 0;
  std::unordered_map<std::string, std::size_t> offsets_;
  std::optional<std::string> duplicate_;
};

}  // namespace vegstream::flight
