// Reading flight paths from JSON (flight_path_json.h; the format in flight/README.md): a Reader
// that turns every problem into "file:line:col: field: what", the walk over the document, and
// the malformed-JSON messages. Writing them back is flight_path_write.cpp.
#include "flight/flight_path_json.h"

#include <cmath>
#include <fstream>
#include <initializer_list>
#include <optional>
#include <sstream>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/json_text.h"
#include "core/text_file.h"

#include "flight/json_positions.h"

namespace vegstream::flight {
namespace {

using nlohmann::json;

std::size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

const char* typeName(const json& v) {
  if (v.is_number()) return "a number";
  if (v.is_string()) return "a string";
  if (v.is_boolean()) return "a boolean";
  if (v.is_null()) return "null";
  if (v.is_array()) return "an array";
  return "an object";
}

// Reads fields of the parsed document, turning each problem into "file:line:col: field: what".
struct Reader {
  const std::string& source;
  const JsonPositions& positions;

  Error fail(const std::string& field, const std::string& problem, const std::string& lineOf) const {
    std::string where = source;
    if (auto lc = positions.find(lineOf)) where += ":" + std::to_string(lc->line) + ":" + std::to_string(lc->column);
    return makeError(ErrorKind::InvalidInput,
                     where + ": " + (field.empty() ? "" : printable(field, 200) + ": ") + problem);
  }

  static std::string child(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }

  std::optional<Error> onlyKnownKeys(const json& obj, const std::string& path,
                                     const std::vector<std::string>& known) const {
    for (const auto& [key, value] : obj.items()) {
      if (std::find(known.begin(), known.end(), key) != known.end()) continue;
      std::string list, hint;
      for (const std::string& k : known) {
        list += (list.empty() ? "" : ", ") + k;
        if (hint.empty() && editDistance(key, k) <= 2) hint = " (did you mean \"" + k + "\"?)";
      }
      return fail(child(path, key), "unknown key \"" + printable(key) + "\"" + hint + "; known keys: " + list,
                  child(path, key));
    }
    return std::nullopt;
  }

  std::optional<Error> expectObject(const json& v, const std::string& path) const {
    if (v.is_object()) return std::nullopt;
    return fail(path.empty() ? "document" : path, std::string("must be an object, found ") + typeName(v), path);
  }

  // obj[key], a `kind` of value that `is` tells apart, as a T: required (fallback empty) or
  // optional, `fallback` where missing.
  template <class T>
  Result<T> field(const json& obj, const std::string& path, const std::string& key, std::optional<T> fallback,
                  const char* kind, bool (json::*is)() const) const {
    const std::string f = child(path, key);
    const auto it = obj.find(key);
    if (it == obj.end()) {
      if (fallback) return std::move(*fallback);
      return fail(f, std::string("missing required ") + kind, path);
    }
    if (!((*it).*is)()) return fail(f, std::string("must be a ") + kind + ", found " + typeName(*it), f);
    return it->get<T>();
  }

  // A required (fallback empty) or optional number.
  Result<double> number(const json& obj, const std::string& path, const std::string& key,
                        std::optional<double> fallback = std::nullopt) const {
    const bool given = obj.contains(key);
    auto v = field<double>(obj, path, key, fallback, "number", &json::is_number);
    if (v && given && !std::isfinite(*v)) return fail(child(path, key), "is not a finite number", child(path, key));
    return v;
  }

  // An optional number without a default: absent stays absent.
  Result<std::optional<double>> optionalNumber(const json& obj, const std::string& path, const std::string& key) const {
    if (!obj.contains(key)) return std::optional<double>();
    auto v = number(obj, path, key);
    if (!v) return v.error();
    return std::optional<double>(*v);
  }

  Result<std::string> string(const json& obj, const std::string& path, const std::string& key,
                             std::optional<std::string> fallback = std::nullopt) const {
    return field<std::string>(obj, path, key, std::move(fallback), "string", &json::is_string);
  }

  // obj[key], a string naming one of `choices` (its value then), `fallback` where missing when
  // given; anything else is an error listing the names.
  template <class E>
  Result<E> choice(const json& obj, const std::string& path, const std::string& key,
                   std::initializer_list<std::pair<const char*, E>> choices,
                   std::optional<std::string> fallback = std::nullopt) const {
    auto s = string(obj, path, key, std::move(fallback));
    if (!s) return s.error();
    std::string names;
    for (const auto& [name, value] : choices) {
      if (*s == name) return value;
      names += std::string(names.empty() ? "" : ", ") + "\"" + name + "\"";
    }
    const std::string f = child(path, key);
    return fail(f, "\"" + printable(*s) + "\" is not one of " + names, f);
  }

  Result<AltRef> altRef(const json& obj, const std::string& path) const {
    return choice<AltRef>(obj, path, "alt_ref", {{"terrain", AltRef::Terrain}, {"msl", AltRef::Msl}}, "terrain");
  }

  // The array at obj[key] (required unless optional), its elements objects.
  Result<const json*> array(const json& obj, const std::string& path, const std::string& key, bool optional) const {
    static const json kEmpty = json::array();
    const std::string f = child(path, key);
    const auto it = obj.find(key);
    if (it == obj.end()) {
      if (optional) return &kEmpty;
      return fail(f, "missing required array", path);
    }
    if (!it->is_array()) return fail(f, std::string("must be an array, found ") + typeName(*it), f);
    for (std::size_t i = 0; i < it->size(); ++i)
      if (auto e = expectObject((*it)[i], f + "[" + std::to_string(i) + "]")) return *e;
    return &*it;
  }
};

#define VEG_TRY_ASSIGN(lhs, expr) \
  do {                            \
    auto r_ = (expr);             \
    if (!r_) return r_.error();   \
    lhs = std::move(r_).value();  \
  } while (false)

template <typename K>
Result<K> readPositionKey(const Reader& r, const json& obj, const std::string& f) {
  K k;
  VEG_TRY_ASSIGN(k.t, r.number(obj, f, "t"));
  VEG_TRY_ASSIGN(k.lat, r.number(obj, f, "lat"));
  VEG_TRY_ASSIGN(k.lon, r.number(obj, f, "lon"));
  VEG_TRY_ASSIGN(k.altM, r.number(obj, f, "alt_m"));
  VEG_TRY_ASSIGN(k.altRef, r.altRef(obj, f));
  return k;
}

// Reads the keyframes array of a collider or wind source (required; an empty one is findProblem's).
Result<std::vector<ColliderKeyframe>> readObjectKeys(const Reader& r, const json& obj, const std::string& f) {
  const json* keys = nullptr;
  VEG_TRY_ASSIGN(keys, r.array(obj, f, "keyframes", false));
  std::vector<ColliderKeyframe> out;
  for (std::size_t i = 0; i < keys->size(); ++i) {
    const std::string kf = f + ".keyframes[" + std::to_string(i) + "]";
    if (auto e = r.onlyKnownKeys((*keys)[i], kf, {"t", "lat", "lon", "alt_m", "alt_ref"})) return *e;
    ColliderKeyframe k;
    VEG_TRY_ASSIGN(k, readPositionKey<ColliderKeyframe>(r, (*keys)[i], kf));
    out.push_back(k);
  }
  return out;
}

Result<Collider> readCollider(const Reader& r, const json& obj, const std::string& f) {
  if (auto e = r.onlyKnownKeys(obj, f, {"name", "shape", "radius_m", "length_m", "keyframes"})) return *e;
  Collider c;
  VEG_TRY_ASSIGN(c.name, r.string(obj, f, "name"));
  VEG_TRY_ASSIGN(
      c.shape, r.choice<Collider::Shape>(obj, f, "shape",
                                         {{"sphere", Collider::Shape::Sphere}, {"capsule", Collider::Shape::Capsule}}));
  VEG_TRY_ASSIGN(c.radiusM, r.number(obj, f, "radius_m"));
  if (c.shape == Collider::Shape::Capsule) {
    VEG_TRY_ASSIGN(c.lengthM, r.number(obj, f, "length_m"));
  } else if (obj.contains("length_m")) {
    return r.fail(f + ".length_m", "only a capsule has a length", f + ".length_m");
  }
  VEG_TRY_ASSIGN(c.keyframes, readObjectKeys(r, obj, f));
  return c;
}

Result<WindSourceSpec> readWindSource(const Reader& r, const json& obj, const std::string& f) {
  if (auto e = r.onlyKnownKeys(obj, f, {"name", "type", "radius_m", "strength_mps", "direction_deg", "keyframes"}))
    return *e;
  WindSourceSpec w;
  VEG_TRY_ASSIGN(w.name, r.string(obj, f, "name"));
  using Type = WindSourceSpec::Type;
  VEG_TRY_ASSIGN(w.type, r.choice<Type>(obj, f, "type",
                                        {{"fan", Type::Fan}, {"whirlwind", Type::Whirlwind}, {"rotor", Type::Rotor}}));
  VEG_TRY_ASSIGN(w.radiusM, r.number(obj, f, "radius_m"));
  VEG_TRY_ASSIGN(w.strengthMps, r.number(obj, f, "strength_mps"));
  if (w.type == WindSourceSpec::Type::Fan) {
    if (!obj.contains("direction_deg"))  // reported at the source, like a missing field (findProblem's words)
      return r.fail(f + ".direction_deg",
                    "a fan needs direction_deg (where it blows towards, degrees clockwise from north)", f);
    double direction = 0.0;
    VEG_TRY_ASSIGN(direction, r.number(obj, f, "direction_deg"));
    w.directionDeg = direction;
  } else if (obj.contains("direction_deg")) {
    const std::string type = obj.at("type").get<std::string>();  // a name choice() accepted
    return r.fail(f + ".direction_deg", "only a fan has a direction (a " + printable(type) + " blows all around)",
                  f + ".direction_deg");
  }
  VEG_TRY_ASSIGN(w.keyframes, readObjectKeys(r, obj, f));
  return w;
}

// The optional top-level "wind" object.
Result<std::optional<WindSection>> readWind(const Reader& r, const json& doc) {
  const auto it = doc.find("wind");
  if (it == doc.end()) return std::optional<WindSection>();
  if (auto e = r.expectObject(*it, "wind")) return *e;
  if (auto e = r.onlyKnownKeys(*it, "wind", {"speed_mps", "direction_deg", "gustiness", "sources"})) return *e;
  WindSection wind;
  VEG_TRY_ASSIGN(wind.speedMps, r.optionalNumber(*it, "wind", "speed_mps"));
  VEG_TRY_ASSIGN(wind.directionDeg, r.optionalNumber(*it, "wind", "direction_deg"));
  VEG_TRY_ASSIGN(wind.gustiness, r.optionalNumber(*it, "wind", "gustiness"));
  const json* sources = nullptr;
  VEG_TRY_ASSIGN(sources, r.array(*it, "wind", "sources", true));
  for (std::size_t i = 0; i < sources->size(); ++i) {
    WindSourceSpec w;
    VEG_TRY_ASSIGN(w, readWindSource(r, (*sources)[i], "wind.sources[" + std::to_string(i) + "]"));
    wind.sources.push_back(std::move(w));
  }
  return std::optional<WindSection>(std::move(wind));
}

// The optional top-level "datetime": ISO 8601 with a zone (geo/datetime.h).
Result<std::optional<geo::DateTime>> readDatetime(const Reader& r, const json& doc) {
  if (!doc.contains("datetime")) return std::optional<geo::DateTime>();
  std::string text;
  VEG_TRY_ASSIGN(text, r.string(doc, "", "datetime"));
  auto t = geo::parseIsoDateTime(text);
  if (!t) return r.fail("datetime", t.error().message, "datetime");
  return std::optional<geo::DateTime>(*t);
}

std::string stemOf(const std::string& source) { return std::filesystem::path(source).stem().string(); }

// Where a problem found on the model is reported: the field itself, else its parent object.
std::string lineFieldFor(const JsonPositions& positions, std::string field) {
  while (!field.empty() && !positions.find(field)) {
    const auto cut = field.find_last_of(".[");
    field = cut == std::string::npos ? "" : field.substr(0, cut);
  }
  return field;
}

// The parsed document → a validated path.
Result<FlightPath> readFlightPath(const json& doc, std::string_view text, const std::string& sourceName) {
  const JsonPositions positions(text);
  const Reader r{sourceName, positions};
  if (const auto& dup = positions.firstDuplicate()) return r.fail(*dup, "key given twice", *dup);
  if (auto e = r.expectObject(doc, "")) return *e;
  if (auto e = r.onlyKnownKeys(doc, "", {"name", "description", "datetime", "keyframes", "colliders", "wind"}))
    return *e;

  FlightPath path;
  VEG_TRY_ASSIGN(path.name, r.string(doc, "", "name", stemOf(sourceName)));
  VEG_TRY_ASSIGN(path.description, r.string(doc, "", "description", std::string()));
  VEG_TRY_ASSIGN(path.datetime, readDatetime(r, doc));
  const json* keys = nullptr;
  VEG_TRY_ASSIGN(keys, r.array(doc, "", "keyframes", false));
  for (std::size_t i = 0; i < keys->size(); ++i) {
    const json& obj = (*keys)[i];
    const std::string f = "keyframes[" + std::to_string(i) + "]";
    if (auto e = r.onlyKnownKeys(obj, f, {"t", "lat", "lon", "alt_m", "alt_ref", "heading", "pitch"})) return *e;
    Keyframe k;
    ColliderKeyframe pos;
    VEG_TRY_ASSIGN(pos, readPositionKey<ColliderKeyframe>(r, obj, f));
    k.t = pos.t, k.lat = pos.lat, k.lon = pos.lon, k.altM = pos.altM, k.altRef = pos.altRef;
    VEG_TRY_ASSIGN(k.headingDeg, r.number(obj, f, "heading"));
    VEG_TRY_ASSIGN(k.pitchDeg, r.number(obj, f, "pitch"));
    path.keyframes.push_back(k);
  }
  const json* colliders = nullptr;
  VEG_TRY_ASSIGN(colliders, r.array(doc, "", "colliders", true));
  for (std::size_t i = 0; i < colliders->size(); ++i) {
    Collider c;
    VEG_TRY_ASSIGN(c, readCollider(r, (*colliders)[i], "colliders[" + std::to_string(i) + "]"));
    path.colliders.push_back(std::move(c));
  }
  VEG_TRY_ASSIGN(path.wind, readWind(r, doc));
  if (auto p = findProblem(path)) return r.fail(p->field, p->problem, lineFieldFor(positions, p->field));
  return path;
}

}  // namespace

Result<FlightPath> parseFlightPath(std::string_view text, const std::string& sourceName) {
  json doc;
  try {
    doc = json::parse(text.begin(), text.end());
  } catch (const json::parse_error& e) {
    // e.byte is 1-based: the position of the character that broke the parse.
    const LineCol lc = lineColAt(text, e.byte > 0 ? e.byte - 1 : 0);
    std::string what = e.what();
    const auto colon = what.find(": ");
    if (colon != std::string::npos) what = what.substr(colon + 2);
    what = printable(what, 2 * kPrintableChars);
    return makeError(ErrorKind::InvalidInput, sourceName + ":" + std::to_string(lc.line) + ":" +
                                                  std::to_string(lc.column) + ": malformed JSON: " + what);
  } catch (const json::exception& e) {
    // Number overflow ("1e999") carries no position: find the number it quotes.
    std::string what = e.what(), where = sourceName;
    const auto colon = what.find("] ");
    if (colon != std::string::npos) what = what.substr(colon + 2);
    const auto open = what.find('\''), close = what.rfind('\'');
    if (open != std::string::npos && close > open) {
      const auto at = text.find(what.substr(open + 1, close - open - 1));
      if (at != std::string_view::npos) {
        const LineCol lc = lineColAt(text, at);
        where += ":" + std::to_string(lc.line) + ":" + std::to_string(lc.column);
      }
    }
    return makeError(ErrorKind::InvalidInput, where + ": malformed JSON: " + printable(what, 2 * kPrintableChars));
  }
  // The walk checks every type before reading; a missed case stays an error value, not an abort.
  try {
    return readFlightPath(doc, text, sourceName);
  } catch (const json::exception& e) {
    return makeError(ErrorKind::InvalidInput, sourceName + ": " + jsonExceptionText(e.what()));
  }
}

Result<FlightPath> loadFlightPath(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::exists(file, ec))
    return makeError(ErrorKind::NotFound, file.string() + ": no such flight path file");
  auto text = readTextFile(file);
  if (!text) return text.error();
  return parseFlightPath(*text, file.string());
}

}  // namespace vegstream::flight
