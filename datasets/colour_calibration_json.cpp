// dataset.json's "imagery.colour_calibration" (colour_calibration_json.h).
#include "datasets/colour_calibration_json.h"

#include <cmath>

#include "datasets/message.h"

namespace vegstream::datasets {
namespace {
using nlohmann::json;
constexpr const char* kField = "imagery.colour_calibration";

Error bad(const std::string& source, const std::string& field, const std::string& problem) {
  return makeError(ErrorKind::InvalidInput, concat("'", source, "': field '", kField, field, "' ", problem));
}

template <size_t N>
Status numbers(const json& obj, const char* key, const std::string& at, const std::string& source, double limit,
               std::array<double, N>& out) {
  auto it = obj.find(key);
  if (it == obj.end()) return bad(source, at + key, "is missing");
  if (!it->is_array() || it->size() != N) return bad(source, at + key, concat("must be an array of ", N, " numbers"));
  for (size_t i = 0; i < N; ++i) {
    if (!(*it)[i].is_number()) return bad(source, at + key, concat("[", i, "] must be a number"));
    out[i] = (*it)[i].get<double>();
    if (!(std::abs(out[i]) <= limit)) return bad(source, at + key, concat("[", i, "] is ", out[i], "; expected within ±", limit));
  }
  return {};
}

Status number(const json& obj, const char* key, const std::string& source, double& out) {
  auto it = obj.find(key);
  if (it == obj.end()) return bad(source, std::string(".statistics.") + key, "is missing");
  if (!it->is_number() || !std::isfinite(it->get<double>()))
    return bad(source, std::string(".statistics.") + key, "must be a finite number");
  out = it->get<double>();
  return {};
}

}  // namespace

json colourCalibrationJson(const ColourCalibrationRecord& c) {
  return {{"method", c.method},
          {"matrix", c.matrix},
          {"offset", c.offset},
          {"statistics",
           {{"pixels", c.pixels},
            {"black", c.black},
            {"white", c.white},
            {"gains", c.gains},
            {"grey", c.grey},
            {"median_chroma", c.medianChroma},
            {"median_luminance", c.medianLuminance},
            {"chroma_gain", c.chromaGain},
            {"exposure", c.exposure}}}};
}

Result<ColourCalibrationRecord> parseColourCalibration(const json& j, const std::string& source) {
  if (!j.is_object()) return bad(source, "", "must be an object or null");
  ColourCalibrationRecord c;
  auto m = j.find("method");
  if (m == j.end() || !m->is_string()) return bad(source, ".method", "must be a string");
  c.method = m->get<std::string>();
  if (c.method != kColourCalibrationMethod)
    return bad(source, ".method", concat("is '", c.method, "'; expected ", kColourCalibrationMethod));
  if (Status s = numbers(j, "matrix", ".", source, 1000.0, c.matrix); !s) return s.error();
  if (Status s = numbers(j, "offset", ".", source, 1000.0, c.offset); !s) return s.error();
  auto st = j.find("statistics");
  if (st == j.end() || !st->is_object()) return bad(source, ".statistics", "must be an object");
  auto px = st->find("pixels");
  if (px == st->end() || !px->is_number_unsigned()) return bad(source, ".statistics.pixels", "must be a count ≥ 0");
  c.pixels = px->get<uint64_t>();
  for (auto [key, out] : {std::pair{"black", &c.black}, {"white", &c.white}, {"gains", &c.gains}, {"grey", &c.grey}})
    if (Status s = numbers(*st, key, ".statistics.", source, 1e6, *out); !s) return s.error();
  for (auto [key, out] : {std::pair{"median_chroma", &c.medianChroma}, {"median_luminance", &c.medianLuminance},
                          {"chroma_gain", &c.chromaGain}, {"exposure", &c.exposure}})
    if (Status s = number(*st, key, source, *out); !s) return s.error();
  return c;
}

}  // namespace vegstream::datasets
