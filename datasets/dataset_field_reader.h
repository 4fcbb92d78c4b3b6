#pragma once
// dataset.json's field access (dataset_format.cpp): a FieldReader that names the source (a file
// or a URL) and the field ("imagery.format") in every error, and VEG_TRY_ASSIGN, which assigns a
// Result's value or returns its error. Header-only, private to datasets/: dataset_format.cpp and
// dataset_layers_json.cpp.

#include <cstdint>
#include <optional>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "core/printable.h"
#include "core/result.h"
#include "datasets/message.h"

namespace vegstream::datasets::dataset_json {
using nlohmann::json;

// Field access that names the source (a file or a URL) and the field ("imagery.format") in
// every error.
class FieldReader {
 public:
  explicit FieldReader(std::string sourceName) : source_(std::move(sourceName)) {}
  const std::string& source() const { return source_; }

  Error bad(const std::string& field, const std::string& problem) const {
    return makeError(ErrorKind::InvalidInput, concat("'", printablePath(source_), "': field '", field, "' ", problem));
  }

  Result<const json*> get(const json& obj, const std::string& key, const std::string& field) const {
    auto it = obj.find(key);
    if (it == obj.end()) return bad(field, "is missing");
    return &*it;
  }
  Result<double> number(const json& obj, const std::string& key, const std::string& field, double lo, double hi) const {
    auto v = get(obj, key, field);
    if (!v) return v.error();
    if (!(*v)->is_number()) return bad(field, "must be a number");
    const double d = (*v)->get<double>();
    if (!(d >= lo && d <= hi)) return bad(field, concat("is ", d, "; expected ", lo, " … ", hi));
    return d;
  }
  Result<int64_t> integer(const json& obj, const std::string& key, const std::string& field, int64_t lo,
                          int64_t hi) const {
    auto v = get(obj, key, field);
    if (!v) return v.error();
    if (!(*v)->is_number_integer()) return bad(field, "must be an integer");
    const int64_t i = (*v)->is_number_unsigned() ? static_cast<int64_t>((*v)->get<uint64_t>()) : (*v)->get<int64_t>();
    if (i < lo || i > hi) return bad(field, concat("is ", i, "; expected ", lo, " … ", hi));
    return i;
  }
  Result<std::string> text(const json& obj, const std::string& key, const std::string& field) const {
    auto v = get(obj, key, field);
    if (!v) return v.error();
    if (!(*v)->is_string()) return bad(field, "must be a string");
    return (*v)->get<std::string>();
  }

 private:
  std::string source_;
};

#define VEG_TRY_ASSIGN(target, expr) \
  do {                               \
    auto r_ = (expr);                \
    if (!r_) return r_.error();      \
    target = std::move(*r_);         \
  } while (0)

// An optional number: absent or null → nullopt; otherwise checked like number().
inline Result<std::optional<double>> optionalNumber(const json& obj, const std::string& key, const std::string& field,
                                                    double lo, double hi, const FieldReader& f) {
  auto it = obj.find(key);
  if (it == obj.end() || it->is_null()) return std::optional<double>{};
  auto v = f.number(obj, key, field, lo, hi);
  if (!v) return v.error();
  return std::optional<double>(*v);
}

}  // namespace vegstream::datasets::dataset_json
