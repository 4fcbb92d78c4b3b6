// `vegstream query` (query_command.h).

#include "app/query_command.h"

#include <cmath>
#include <cstdio>
#include <iostream>

#include <nlohmann/json.hpp>

#include "app/exit_codes.h"
#include "datasets/dataset_reader.h"

namespace vegstream::app {

int runQuery(const QueryOptions& options, const Logger& log) {
  auto reader = datasets::DatasetReader::open(options.dataset);
  if (!reader) return reportError(log, reader.error());
  auto height = reader->heightAt(options.latDeg, options.lonDeg);
  if (!height) return reportError(log, height.error());
  if (std::isnan(*height)) {
    std::string m = "dataset ";
    m += options.dataset;
    m += " has no elevation data at lat ";
    m += std::to_string(options.latDeg);
    m += ", lon ";
    m += std::to_string(options.lonDeg);
    return reportError(log, makeError(ErrorKind::InvalidInput, m));
  }
  auto color = reader->colorAt(options.latDeg, options.lonDeg);
  if (!color) return reportError(log, color.error());

  nlohmann::json out = {{"dataset", reader->meta().name},
                        {"lat", options.latDeg},
                        {"lon", options.lonDeg},
                        {"height_m", *height}};
  if (*color) {
    const auto& c = **color;
    char hex[8];
    std::snprintf(hex, sizeof(hex), "#%02x%02x%02x", c[0], c[1], c[2]);
    out["color"] = {{"r", c[0]}, {"g", c[1]}, {"b", c[2]}, {"hex", hex}};
  } else {
    out["color"] = nullptr;
  }
  std::cout << out.dump(2) << "\n";
  return kExitOk;
}

}  // namespace vegstream::app
