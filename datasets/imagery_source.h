#pragma once
// Imagery as the importer resamples it, window by window: one RGB(A)/grey raster (or a mosaic of
// several; any GDAL format, bands chosen with --bands) or three single-band files (R, G, B) on one
// grid, turned into 3-channel windows with NaN where there is no data, their numbers given a
// meaning by the radiometry (radiometry.h, --radiometry), chosen once from whole-raster
// statistics (the overview, kStatisticsPixels):
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
#include "datasets/raster.h"
#include "datasets/raster_source.h"
#include "datasets/source_grid.h"
#include "datasets/radiometry.h"
#include "datasets/colour_calibration.h"

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
  std::vector<std::string> files;              // --imagery (several: a mosaic)
  std::vector<int> bandNumbers;                // --bands R,G,B of --imagery (1-based); empty: GDAL's non-alpha bands
  std::vector<std::string> bands;              // --imagery-bands R,G,B: three single-band files on one grid
  std::optional<geo::Crs> assumeCrs;           // --imagery-crs
  std::optional<Stretch> stretch;              // --stretch (auto radiometry then stretches)
  RadiometryOptions radiometry;                // --radiometry, --reflectance-scale, --reflectance-offset
  bool given() const { return !files.empty() || !bands.empty(); }
  // The file (or first band file) as the user wrote it, for messages and dataset.json.
  std::string label() const;
};

// Whole-raster statistics come from at most this many pixels (an exact read below it).
inline constexpr uint64_t kStatisticsPixels = 4'000'000;

// One window of prepared imagery: 3 channels, NaN = no data, in the meaning of `linear`; and the
// red channel's raw values (before any radiometric change) for NDVI.
struct ImageryWindow {
  Raster colour;
  std::vector<float> rawRed;  // one per pixel of `colour`
};

class PreparedImagery {
 public:
  // Opens the sources, checks them (one grid for band files), takes the statistics from the
  // overview and chooses the radiometry. Errors as RasterSource::open's, plus: bands of
  // different grids / CRSs, a band file with more than one band, imagery with no valid pixel,
  // and chooseRadiometry's.
  static Result<PreparedImagery> open(const ImageryInput& input, const Logger& log);

  const RasterSource& source() const { return sources_.front(); }  // the grid all share
  // The imagery around `pixels` (whole-raster pixel coordinates of source()), with `margin`
  // samples more, decimated beyond maxSide. nullopt: none of them on the raster.
  Result<std::optional<ImageryWindow>> window(const SourceGrid& grid, const std::vector<glm::dvec2>& pixels,
                                              int margin, int maxSide) const;

  bool linear = false;  // linear 0 … 1 when true, else sRGB-encoded 0 … 255
  std::array<std::array<double, 2>, 3> ranges{
      {{0.0, 255.0}, {0.0, 255.0}, {0.0, 255.0}}};  // stretch: per band, the values mapped to 0 and 255
  bool stretched = false;
  RadiometryRecord radiometry;   // for dataset.json (deshading filled in by the importer)
  ColourCalibrationRecord colourCalibration;  // from the converted overview (colour_calibration.h)
  std::string radiometryChoice;  // what was chosen and why, for the importer's log
  std::string description;       // for dataset.json's sources

 private:
  Raster merged(std::vector<Raster> parts) const;  // 3 channels of raw values, NaN = no data
  void convert(Raster& r) const;                    // raw values → the chosen meaning
  static ColourCalibrationRecord calibrationOf(const PreparedImagery& p, Raster overview);

  std::vector<RasterSource> sources_;  // one file (or mosaic), or three band files
  RadiometryMethod method_ = RadiometryMethod::Srgb;
  double scale_ = 1.0, offset_ = 0.0;
  std::array<double, 3> dark_{};
};

}  // namespace vegstream::datasets
