#pragma once
// The GDAL calls behind RasterSource (raster_source.h) that read pixels and metadata: one
// window of chosen bands into a Raster with the masks applied, the units of heights, and the
// acquisition time. Only raster_source.cpp includes this (it exposes GDAL types).

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include "core/result.h"
#include "datasets/raster.h"

namespace vegstream::datasets {

struct PixelWindow {
  int x0, y0, w, h;  // whole-raster pixels; the buffer is out.width × out.height
};

// Reads `bands` (1-based) of window `win` into out.samples (pixel-interleaved float, already
// sized; nearest-neighbour when the buffer is smaller than the window). Each value becomes
// value · scale[b] + offset[b], times verticalScale; a pixel is NaN where the band's GDAL mask
// is 0 (nodata value, alpha, per-dataset mask), or, with nodataOverride, where it holds that
// value. The error's message is the bare reason (the caller names the file).
Status readWindow(GDALDataset& d, const std::vector<int>& bands, const std::vector<double>& scale,
                  const std::vector<double>& offset, std::optional<double> nodataOverride, double verticalScale,
                  const PixelWindow& win, Raster& out);

// Metres per unit of a band whose unit type is `unit` ("ft", "foot", "US survey foot", "m", …);
// `current` when the unit says nothing.
double bandUnitScale(const char* unit, double current);
// Metres per unit of a compound CRS's vertical axis; `current` when it has none.
double verticalUnitScale(const OGRSpatialReference& srs, double current);

// When the imagery was taken, as its metadata says (see RasterSource::acquisitionDatetime).
std::optional<std::string> acquisitionDatetimeOf(GDALDataset& d);

}  // namespace vegstream::datasets
