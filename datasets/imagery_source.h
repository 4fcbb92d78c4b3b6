#pragma once
// Imagery as the importer resamples it: one RGB(A)/grey GeoTIFF or three single-band files
// (R, G, B) on one grid, turned into a 3-channel raster with NaN where there is no data, its
// numbers given a meaning by the radiometry (radiometry.h, --radiometry):
// - reflectance: linear surface reflectance 0 … 1 (PreparedImagery::linear);
// - srgb: 8-bit sRGB-encoded values 0 … 255 as stored;
// - stretch: 0 … 255 display values, each band stretched between the p-th and q-th percentiles
//   of its valid pixels (--stretch p1,p99, the default) or between fixed values (--stretch LO,HI).

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/log.h"
#include "core/result.h"
#include "datasets/dataset_format.h"
#include "datasets/geotiff_reader.h"
#include "datasets/radiometry.h"

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
  std::optional<Stretch> stretch;             // --stretch (auto radiometry then stretches)
  RadiometryOptions radiometry;               // --radiometry, --reflectance-scale, --reflectance-offset
  uint64_t maxPixels = 400'000'000;
  // Keep the red channel's raw values (PreparedImagery::rawRed): NDVI needs the digital numbers
  // the stretch throws away (ndvi_source.h).
  bool keepRawRed = false;
};

struct PreparedImagery {
  Raster raster;  // 3 channels, NaN = no data: linear 0 … 1 when `linear`, else sRGB-encoded 0 … 255
  bool linear = false;
  std::array<std::array<double, 2>, 3> ranges{
      {{0.0, 255.0}, {0.0, 255.0}, {0.0, 255.0}}};  // stretch: per band, the values mapped to 0 and 255
  bool stretched = false;
  RadiometryRecord radiometry;   // for dataset.json (deshading filled in by the importer)
  std::string radiometryChoice;  // what was chosen and why, for the importer's log
  std::string description;       // for dataset.json's sources
  // With ImageryInput::keepRawRed: channel 0 (the first of --imagery-bands, channel 0 of
  // --imagery) as read, before the stretch, one value per pixel of `raster`, NaN = no data.
  // Empty otherwise.
  std::vector<float> rawRed;
};

// Errors as readGeoTiff's, plus: bands of different grids / CRSs, a band with more than one
// channel, imagery with no valid pixel, and chooseRadiometry's.
Result<PreparedImagery> prepareImagery(const ImageryInput& input, const Logger& log);

}  // namespace vegstream::datasets
