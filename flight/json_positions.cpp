#include "flight/json_positions.h"

#include <algorithm>

namespace vegstream::flight {

LineCol lineColAt(std::string_view text, std::size_t offset) {
  offset = std::min(offset, text.size());
  LineCol lc;
  for (std::size_t i = 0; i < offset; ++i) {
    if (text[i] == '\n') {
      ++lc.line;
      lc.column = 1;
    } else {
      ++lc.column;
    }
  }
  return lc;
}

JsonPositions::JsonPositions(std::string_view text) : text_(text) {
  skipSpace();
  if (pos_ < text_.size()) value("", 0);
}

std::optional<LineCol> JsonPositions::find(const std::string& path) const {
  const auto it = offsets_.find(path);
  if (it == offsets_.end()) return std::nullopt;
  return lineColAt(text_, it->second);
}

void JsonPositions::skipSpace() {
  while (pos_ < text_.size() &&
         (text_[pos_] == ' ' || text_[pos_] == '\t' || text_[pos_] == '\n' || text_[pos_] == '\r'))
    ++pos_;
}

std::string JsonPositions::readString() {
  std::string out;
  ++pos_;  // opening quote
  while (pos_ < text_.size() && text_[pos_] != '"') {
    if (text_[pos_] == '\\' && pos_ + 1 < text_.size()) {
      out += text_[pos_ + 1];  // good enough for keys: vegstream's keys are plain ASCII
      pos_ += 2;
      continue;
    }
    out += text_[pos_++];
  }
  ++pos_;  // closing quote
  return out;
}

void JsonPositions::skipNested() {
  int open = 0;
  while (pos_ < text_.size()) {
    const char c = text_[pos_];
    if (c == '"') {
      readString();
      continue;
    }
    ++pos_;
    if (c == '{' || c == '[') ++open;
    if ((c == '}' || c == ']') && --open == 0) return;
  }
}

void JsonPositions::value(const std::string& path, int depth) {
  // A path longer than kMaxIndexedPath is not indexed, nor is anything under it: every value
  // under a long key repeated that key in its own path (a 30 000-byte key over an array of
  // 17 000 numbers made half a gigabyte of paths, quadratic in the text; found profiling the
  // flight_path fuzz target). Such a field has no line of its own: lineFieldFor gives its nearest
  // indexed parent's, other look-ups none.
  const bool indexed = path.size() <= kMaxIndexedPath;
  if (indexed && !offsets_.emplace(path, pos_).second && !duplicate_) duplicate_ = path;
  if (pos_ >= text_.size()) return;
  const char c = text_[pos_];
  if (c == '"') {
    readString();
  } else if ((c == '{' || c == '[') && (depth >= 64 || !indexed)) {
    skipNested();
  } else if (c == '{' || c == '[') {
    const bool object = c == '{';
    const char close = object ? '}' : ']';
    ++pos_;
    for (std::size_t index = 0;; ++index) {
      skipSpace();
      if (pos_ >= text_.size()) return;
      if (text_[pos_] == close) break;
      if (text_[pos_] == ',') {
        ++pos_;
        skipSpace();
      }
      std::string child;
      if (object) {
        const std::string key = readString();
        skipSpace();
        ++pos_;  // ':'
        skipSpace();
        child = path.empty() ? key : path + "." + key;
      } else {
        child = path + "[" + std::to_string(index) + "]";
      }
      value(child, depth + 1);
    }
    ++pos_;  // closing bracket
  } else {
    while (pos_ < text_.size() && text_[pos_] != ',' && text_[pos_] != '}' && text_[pos_] != ']' &&
           text_[pos_] != ' ' && text_[pos_] != '\n' && text_[pos_] != '\r' && text_[pos_] != '\t')
      ++pos_;
  }
}

}  // namespace vegstream::flight
