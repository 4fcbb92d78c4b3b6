#pragma once
// Building one-line error messages without `"literal" + std::string`, which GCC 12 at -O3
// flags with a false -Wrestrict (bug 105651): concat() appends its pieces to one string.

#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>
#include <type_traits>

namespace vegstream::datasets {

namespace detail {
inline void appendPiece(std::string& s, std::string_view v) { s += v; }
inline void appendPiece(std::string& s, const std::string& v) { s += v; }
inline void appendPiece(std::string& s, const char* v) { s += v; }
inline void appendPiece(std::string& s, char v) { s += v; }
inline void appendPiece(std::string& s, const std::filesystem::path& p) {
  s += '\'';
  s += p.string();
  s += '\'';
}
template <typename T>
requires std::is_integral_v<T>
void appendPiece(std::string& s, T v) { s += std::to_string(v); }
template <typename T>
requires std::is_floating_point_v<T>
void appendPiece(std::string& s, T v) {
  char buf[40];
  std::snprintf(buf, sizeof(buf), "%.10g", static_cast<double>(v));
  s += buf;
}
}  // namespace detail

// concat("tile ", path, " has ", 3, " channels"): paths are quoted, numbers printed.
template <typename... Pieces>
std::string concat(const Pieces&... pieces) {
  std::string s;
  (detail::appendPiece(s, pieces), ...);
  return s;
}

}  // namespace vegstream::datasets
