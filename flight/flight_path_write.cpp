// flightPathToJson (flight_path_json.h): a flight path as the JSON text parseFlightPath reads
// back to the same path, one keyframe per line, numbers to fixed decimals.
#include "flight/flight_path_json.h"

#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace vegstream::flight {
namespace {

std::string fmt(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

// A string as a JSON string literal.
std::string str(const std::string& s) { return nlohmann::json(s).dump(); }

// The fields of one keyframe's position: "t": …, "lat": …, "lon": …, "alt_m": …, "alt_ref": ….
std::string position(double t, double lat, double lon, double alt, AltRef a) {
  const char* ref = a == AltRef::Terrain ? "\"terrain\"" : "\"msl\"";
  return "\"t\": " + fmt(t, 3) + ", \"lat\": " + fmt(lat, 7) + ", \"lon\": " + fmt(lon, 7) +
         ", \"alt_m\": " + fmt(alt, 3) + ", \"alt_ref\": " + ref;
}

// The keyframes of a collider or a wind source, one a line after `indent`.
std::string objectKeys(const std::vector<ColliderKeyframe>& keys, const std::string& indent) {
  std::string out;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const ColliderKeyframe& k = keys[i];
    out += indent + "{" + position(k.t, k.lat, k.lon, k.altM, k.altRef) + "}" + (i + 1 < keys.size() ? ",\n" : "\n");
  }
  return out;
}

// The "colliders" array, after the keyframes.
std::string collidersJson(const std::vector<Collider>& colliders) {
  std::string out = ",\n  \"colliders\": [\n";
  for (std::size_t c = 0; c < colliders.size(); ++c) {
    const Collider& col = colliders[c];
    const bool capsule = col.shape == Collider::Shape::Capsule;
    out += "    {\"name\": " + str(col.name) + ", \"shape\": " + (capsule ? "\"capsule\"" : "\"sphere\"") +
           ", \"radius_m\": " + fmt(col.radiusM, 3) + (capsule ? ", \"length_m\": " + fmt(col.lengthM, 3) : "") +
           ",\n     \"keyframes\": [\n";
    out += objectKeys(col.keyframes, "       ");
    out += std::string("     ]}") + (c + 1 < colliders.size() ? ",\n" : "\n");
  }
  return out + "  ]";
}

// The "wind" object: its optional numbers, then its sources.
std::string windJson(const WindSection& w) {
  std::string fields;
  auto add = [&](const char* key, const std::optional<double>& v) {
    if (v) fields += std::string(fields.empty() ? "" : ", ") + "\"" + key + "\": " + fmt(*v, 3);
  };
  add("speed_mps", w.speedMps);
  add("direction_deg", w.directionDeg);
  add("gustiness", w.gustiness);
  std::string out = ",\n  \"wind\": {" + fields;
  if (w.sources.empty()) return out + "}";
  out += std::string(fields.empty() ? "" : ",") + "\n    \"sources\": [\n";
  for (std::size_t s = 0; s < w.sources.size(); ++s) {
    const WindSourceSpec& src = w.sources[s];
    const char* type = src.type == WindSourceSpec::Type::Fan         ? "\"fan\""
                       : src.type == WindSourceSpec::Type::Whirlwind ? "\"whirlwind\""
                                                                     : "\"rotor\"";
    out += "      {\"name\": " + str(src.name) + ", \"type\": " + type + ", \"radius_m\": " + fmt(src.radiusM, 3) +
           ", \"strength_mps\": " + fmt(src.strengthMps, 3) +
           (src.directionDeg ? ", \"direction_deg\": " + fmt(*src.directionDeg, 3) : "") +
           ",\n       \"keyframes\": [\n";
    out += objectKeys(src.keyframes, "         ");
    out += std::string("       ]}") + (s + 1 < w.sources.size() ? ",\n" : "\n");
  }
  return out + "    ]\n  }";
}

}  // namespace

std::string flightPathToJson(const FlightPath& path) {
  std::string out = "{\n  \"name\": " + str(path.name) + ",\n";
  if (!path.description.empty()) out += "  \"description\": " + str(path.description) + ",\n";
  if (path.datetime) out += "  \"datetime\": " + str(geo::formatIsoDateTime(*path.datetime)) + ",\n";
  out += "  \"keyframes\": [\n";
  for (std::size_t i = 0; i < path.keyframes.size(); ++i) {
    const Keyframe& k = path.keyframes[i];
    out += "    {" + position(k.t, k.lat, k.lon, k.altM, k.altRef) + ", \"heading\": " + fmt(k.headingDeg, 3) +
           ", \"pitch\": " + fmt(k.pitchDeg, 3) + "}" + (i + 1 < path.keyframes.size() ? ",\n" : "\n");
  }
  out += "  ]";
  if (!path.colliders.empty()) out += collidersJson(path.colliders);
  if (path.wind) out += windJson(*path.wind);
  return out + "\n}\n";
}

}  // namespace vegstream::flight
