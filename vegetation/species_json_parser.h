#pragma once
// The species catalog's field reader: a Parser that records the first problem with its field
// path (and stops there, so a user sees one message naming the file and the field), and the
// checked readers of numbers, counts and "#rrggbb" colours built on it. Header-only, private to
// vegetation/: species_catalog.cpp (the catalog) and species_entry_parse.cpp (one species).

#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>

#include <nlohmann/json.hpp>

#include "core/printable.h"
#include "core/result.h"
#include "vegetation/species_catalog.h"

namespace vegstream::vegetation::species_json {
using nlohmann::json;

// A number as the messages print it.
inline std::string fmt(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// Reads a catalog's fields under their paths; fail() keeps the first problem only.
class Parser {
 public:
  explicit Parser(std::string source) : source_(std::move(source)) {}

  bool fail(const std::string& path, const std::string& problem) {
    // The path holds keys from the file: escaped and bounded like any value from data.
    if (!error_) error_ = makeError(ErrorKind::InvalidInput, source_ + ": " + printable(path, 200) + ": " + problem);
    return false;
  }
  const Error& error() const { return *error_; }
  // fail() as a value to return.
  Error failed(const std::string& path, const std::string& problem) {
    fail(path, problem);
    return *error_;
  }

  bool onlyKeys(const json& obj, const std::string& path, std::initializer_list<std::string_view> allowed) {
    for (auto it = obj.begin(); it != obj.end(); ++it) {
      bool known = false;
      for (std::string_view a : allowed) known = known || it.key() == a;
      if (!known) {
        std::string list;
        for (std::string_view a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
        return fail(join(path, it.key()), "unknown key (allowed here: " + list + ")");
      }
    }
    return true;
  }

  bool object(const json& v, const std::string& path) { return v.is_object() || fail(path, "must be an object"); }

  // A number in [lo, hi] (closed; open bounds are checked by the caller's message).
  bool number(const json& obj, std::string_view key, const std::string& path, float& out, bool required = true) {
    const auto it = obj.find(key);
    if (it == obj.end()) return !required || fail(join(path, key), "is missing");
    if (!it->is_number()) return fail(join(path, key), "must be a number");
    const double d = it->get<double>();
    if (!std::isfinite(d) || std::abs(d) > 1e30) return fail(join(path, key), "must be a finite number");
    out = static_cast<float>(d);
    return true;
  }

  bool range(const json& obj, std::string_view key, const std::string& path, FloatRange& out, double lo, bool loOpen,
             double hi, const char* what) {
    const std::string p = join(path, key);
    const auto it = obj.find(key);
    if (it == obj.end()) return fail(p, "is missing");
    if (!object(*it, p) || !onlyKeys(*it, p, {"min", "max"})) return false;
    if (!number(*it, "min", p, out.min) || !number(*it, "max", p, out.max)) return false;
    for (const auto& [name, v] : {std::pair{"min", out.min}, std::pair{"max", out.max}}) {
      const bool low = loOpen ? !(v > lo) : !(v >= lo);
      if (low || v > hi) return fail(p + "." + name, std::string("must be ") + what + " (got " + fmt(v) + ")");
    }
    if (out.min > out.max) return fail(p + ".max", "must be ≥ min (got " + fmt(out.max) + " < " + fmt(out.min) + ")");
    return true;
  }

  static std::string join(const std::string& path, std::string_view key) {
    return path.empty() ? std::string(key) : path + "." + std::string(key);
  }

 private:
  std::string source_;
  std::optional<Error> error_;
};

// A hex digit's value; −1 when c is none.
inline int hexDigit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// "#rrggbb" → its three bytes; false when it is not one.
inline bool parseHexColour(const json& v, int (&rgb)[3]) {
  const std::string text = v.is_string() ? v.get<std::string>() : "";
  if (text.size() != 7 || text[0] != '#') return false;
  for (size_t i = 0; i < 3; ++i) {
    const int hi = hexDigit(text[1 + 2 * i]), lo = hexDigit(text[2 + 2 * i]);
    if (hi < 0 || lo < 0) return false;
    rgb[i] = hi * 16 + lo;
  }
  return true;
}

// An optional whole number in [lo, hi] (default kept when absent).
inline bool parseCount(Parser& ps, const json& obj, std::string_view key, const std::string& path, uint32_t& out,
                       uint32_t lo, uint32_t hi) {
  const auto it = obj.find(key);
  if (it == obj.end()) return true;
  const std::string p = Parser::join(path, key);
  if (!it->is_number_integer() && !(it->is_number_float() && std::floor(it->get<double>()) == it->get<double>()))
    return ps.fail(p, "must be a whole number");
  const double v = it->get<double>();
  if (v < lo || v > hi)
    return ps.fail(p, "must be " + std::to_string(lo) + " … " + std::to_string(hi) + " (got " + fmt(v) + ")");
  out = static_cast<uint32_t>(v);
  return true;
}

// An optional number in [lo, hi], or (lo, hi] when loOpen (default kept when absent).
inline bool parseBounded(Parser& ps, const json& obj, std::string_view key, const std::string& path, float& out,
                         double lo, bool loOpen, double hi, const char* what, bool required = false) {
  if (!ps.number(obj, key, path, out, required)) return false;
  if ((loOpen ? !(out > lo) : !(out >= lo)) || out > hi)
    return ps.fail(Parser::join(path, key), std::string("must be ") + what + " (got " + fmt(out) + ")");
  return true;
}

}  // namespace vegstream::vegetation::species_json
