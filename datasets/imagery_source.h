#pragma once
// Imagery as the importer resamples it: one RGB(A)/grey GeoTIFF or three single-band files
// (R, G, B) on one grid, turned into a 3-channel raster of 0 … 255 floats with NaN where there
// is no data. Landsat-like UInt16 digital numbers are stretched to 0 … 255 between the p-th
// and q-th percentiles of each band's valid pixels (--stretch p1,p99) or between fixed values
// (--stretch LO,HI); 8-bit imagery passes through unless a stretch is asked for, and imagery
// beyond 0 … 255 without a stretch gets p1,p99 with a note.

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/log.h"
#include "core/result.h"
#include "datasets/geotiff_reader.h"

namespace vegstream::datasets {

struct Stretch {
  enum class Kind { Percentile, Fixed };
  Kind kind = Kind::Percentile;
  double lo = 1.0;  // percent (Percentile) or sample value (Fixed)
  double hi = 99.0;
};

// "p1,p99" (0 ≤ p < q ≤ 100) or "6700,18300" (LO < HI). Errors name the text.
Result<Stretch> parseStretch(const std::string& text);

struct ImageryInput {
  std::optional<std::filesystem::path> file;  // --imagery
  std::vector<std::filesystem::path> bands;   // --imagery-bands R,G,B
  std::optional<int> assumeEpsg;              // --imagery-crs
  std::optional<Stretch> stretch;
  uint64_t maxPixels = 400'000'000;
  // Keep the red channel's raw values (PreparedImagery::rawRed): NDVI needs the digital numbers
  // the stretch throws away (ndvi_source.h).
  bool keepRawRed = false;
};

struct PreparedImagery {
  Raster raster;                                // 3 channels, 0 … 255, NaN = no data
  std::array<std::array<double, 2>, 3> ranges;  // per band: the values mapped to 0 and 255
  bool stretched = false;
  std::string description;  // for dataset.json's sources
  // With ImageryInput::keepRawRed: channel 0 (the first of --imagery-bands, channel 0 of
  // --imagery) as read, before the stretch, one value per pixel of `raster`, NaN = no data.
  // Empty otherwise.
  std::vector<float> rawRed;
};

// Errors as readGeoTiff's, plus: bands of different grids / CRSs, a band with more than one
// channel, imagery with no valid pixel.
Result<PreparedImagery> prepareImagery(const ImageryInput& input, const Logger& log);

}  // namespace vegstream::datasets
