#pragma once
// `vegstream query DATASET --lat LAT --lon LON`: the height (bilinear between pixel centres,
// at the finest zoom with data) and the base colour of the imagery at one point, as JSON on
// stdout. (The species the colour score picks joins once vegetation/ exists.)

#include <string>

#include "core/log.h"

namespace vegstream::app {

struct QueryOptions {
  std::string dataset;
  double latDeg = 0.0;
  double lonDeg = 0.0;
};

// Exit code: 0; 2 for a missing / bad dataset, a point outside its bounds or without data.
int runQuery(const QueryOptions& options, const Logger& log);

}  // namespace vegstream::app
