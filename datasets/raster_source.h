#pragma once
// A raster source as the importer reads it: one or several files or URLs, opened through GDAL
// (any raster driver GDAL has: GeoTIFF, COG, VRT, JP2, HGT, IMG, …), read one window at a time
// so that memory never grows with the raster's size.
//
// - Several inputs mosaic into one raster (an in-memory VRT, gdalbuildvrt's rules: one CRS, the
//   same band count; the average resolution).
// - http:// and https:// inputs are read through GDAL's /vsicurl/ (HTTP range requests: a COG
//   is read tile by tile), with GDAL's retries set as the streaming retry policy's
//   (geo/gdal_quiet.h).
// - Bands: `bands` (1-based) picks them; without it, every band GDAL does not call alpha.
// - Ceilings, checked at open from the header before GDAL reads anything: at most 64 bands taken,
//   256 MiB in one GDAL block (every band of the file when interleaved by pixel), 16 M blocks over
//   the bands taken; past one, InvalidInput naming the file (a block of gigabytes or thousands of
//   bands is what a damaged or hostile file of a few hundred bytes can claim).
// - No data: a band's mask as GDAL defines it (its nodata value, a declared alpha band, a
//   per-dataset mask) becomes NaN; `nodataOverride` replaces that with a value of our own.
// - Heights (`heights`): the band's scale and offset applied, and values in feet (the band's
//   unit, or a compound CRS's vertical unit) converted to metres.
// - CRS: the file's, unless `assumeCrs` is given (which wins); a file without one is an error
//   telling the user to state it with `crsFlag`.
//
// Every failure is an Error naming the input and GDAL's reason: missing file (NotFound), a file
// GDAL cannot open or read (a truncated file fails on the window that needs the missing bytes),
// no georeference, GCPs only (Unsupported), a mosaic of different CRSs, bands out of range.
// Thread-safe: each thread reading gets its own GDAL handle from a pool.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/result.h"
#include "datasets/raster.h"
#include "geo/crs.h"

namespace vegstream::datasets {

struct SourceOptions {
  std::string flag = "--dem";          // the option that named the inputs, for messages
  std::string crsFlag = "--dem-crs";   // the option that states a CRS, for messages
  std::optional<geo::Crs> assumeCrs;   // overrides the file's CRS
  std::optional<double> nodataOverride;
  std::vector<int> bands;              // 1-based; empty: every band that is not alpha
  bool heights = false;                // scale/offset and feet → metres
};

// "https://…" → "/vsicurl/https://…"; anything else as it is.
std::string gdalPathOf(const std::string& input);
bool isUrl(const std::string& input);

class RasterSource {
 public:
  static Result<RasterSource> open(const std::vector<std::string>& inputs, const SourceOptions& options);

  const std::string& label() const;  // the input (or "A + N more"), for messages
  int width() const;
  int height() const;
  int channels() const;              // bands read
  const GeoReference& georef() const;
  const geo::Crs& crs() const;       // georef().crs, always set once open succeeded
  const std::string& driver() const; // GDAL's short name ("GTiff", "VRT", "JP2OpenJPEG", …)
  double verticalScale() const;      // metres per stored unit (heights), 1 otherwise
  // The acquisition time the file's metadata gives (GDAL's IMAGERY domain ACQUISITIONDATETIME,
  // or EXIF DateTimeOriginal with its offset), as ISO 8601 with a zone; nullopt when none.
  std::optional<std::string> acquisitionDatetime() const;
  // "1128x1428 px, 3 bands UInt16, GTiff" — for dataset.json's sources.
  std::string description() const;

  // The pixels [x0, x0 + w) × [y0, y0 + h) (clamped to the raster; w, h > 0 after clamping),
  // read decimated so that the buffer has at most maxSide pixels on a side (nearest
  // neighbour; 0: never decimated). Errors name the input.
  Result<Raster> read(int x0, int y0, int w, int h, int maxSide = 0) const;
  // The whole raster, decimated (nearest) to at most maxPixels buffer pixels: what whole-raster
  // statistics (percentiles, dark objects) are taken from. Exact for rasters that small.
  Result<Raster> readOverview(uint64_t maxPixels) const;

  struct Shared;

 private:
  std::shared_ptr<Shared> s_;
};

// The whole of one raster in memory (RasterSource::open + read): for small files and tests.
Result<Raster> readWholeRaster(const std::string& input, const SourceOptions& options = {});

}  // namespace vegstream::datasets
