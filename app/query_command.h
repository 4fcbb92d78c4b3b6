#pragma once
// `vegstream query DATASET --lat LAT --lon LON [--species FILE]`: the height (bilinear between
// pixel centres, at the finest zoom with data), the base colour of the imagery at one point and
// the species the colour score picks there (core seed ../shared/seeds/001_3eca9f2c7752e4fb.txt
// §3.3 eq. 16–18, vegetation/species_choice.h), as JSON on stdout:
//   "species": best species' name (null without imagery or when nothing passes its threshold),
//   "species_bare": whether that is bare soil (a seed there grows nothing),
//   "species_candidates": [{"name", "bare", "probability"}, …] the two best and the chance each
//   is drawn, s_i / (s0 + s1).
//   "excess_green": ExG of the colour through the dataset's colour calibration (4 decimals;
//   vegetation/colour_calibration.h): the species choice sees that calibrated colour, as plants do.
//   "ndvi": the NDVI layer's value (4 decimals) or null,
//   "landcover": {"code", "name", "kind", "scheme"} of the landcover layer's class at the point
//   (nearest pixel; name and kind null for a code the scheme does not know) or null.
// The catalog is the embedded config/species.json unless --species names another.

#include <string>

#include "core/log.h"

namespace vegstream::app {

struct QueryOptions {
  std::string dataset;
  double latDeg = 0.0;
  double lonDeg = 0.0;
  std::string speciesFile;  // empty: the embedded default catalog
};

// Exit code: 0; 2 for a missing / bad species file (one message naming file and field), a missing / bad dataset, a point outside its bounds or without data.
int runQuery(const QueryOptions& options, const Logger& log);

}  // namespace vegstream::app
