#pragma once
// Reading georeferenced rasters (GeoTIFF) through OpenImageIO's metadata.
//
// Contract: readGeoTiff never crashes on bad input; every failure is an Error whose message
// names the file and the problem (missing file, not a TIFF, truncated, no georeference,
// unsupported CRS, more pixels than ReadOptions::maxPixels — refused before allocating).

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/result.h"

namespace vegstream::datasets {

// GTRasterType: whether a sample stands for an area (its tie point is the pixel's corner) or
// for a point (its tie point is the pixel's centre).
enum class RasterType { PixelIsArea, PixelIsPoint };

struct GeoReference {
  int epsg = 0;                // 4326, 4269, 3857, 326xx, 327xx …; 0 when the file names none
  std::string crsDescription;  // citation / description found in the file, for messages
  RasterType rasterType = RasterType::PixelIsArea;
  // Affine map from continuous pixel coordinates (col, row), with (0, 0) the top-left
  // *corner* of the first pixel whatever the raster type (the PixelIsPoint half-pixel shift is
  // already applied), to CRS coordinates:
  //   x = t[0] + t[1]·col + t[2]·row,   y = t[3] + t[4]·col + t[5]·row
  // The centre of pixel (i, j) is therefore at (i + 0.5, j + 0.5).
  std::array<double, 6> transform{0, 1, 0, 0, 0, -1};

  // CRS coordinates of the centre of pixel (col, row).
  std::array<double, 2> pixelCentre(double col, double row) const {
    const double c = col + 0.5, r = row + 0.5;
    return {transform[0] + transform[1] * c + transform[2] * r, transform[3] + transform[4] * c + transform[5] * r};
  }
};

struct Raster {
  std::filesystem::path path;
  int width = 0;
  int height = 0;
  int channels = 0;
  std::vector<float> samples;    // row-major from the top row, channels interleaved
  std::optional<double> nodata;  // GDAL_NODATA, or ReadOptions::nodataOverride
  GeoReference georef;

  float at(int col, int row, int channel = 0) const {
    return samples[(static_cast<size_t>(row) * static_cast<size_t>(width) + static_cast<size_t>(col)) *
                       static_cast<size_t>(channels) +
                   static_cast<size_t>(channel)];
  }
  bool isNodata(float v) const { return v != v || (nodata && static_cast<double>(v) == *nodata); }
};

struct ReadOptions {
  // The CRS the user states (--dem-crs EPSG:4326): used when the file's GeoKey directory is
  // missing or corrupt but its tie point and pixel scale are sound; overrides the file's CRS.
  std::optional<int> assumeEpsg;
  std::optional<double> nodataOverride;
  // Refuse rasters with more pixels than this before allocating anything.
  uint64_t maxPixels = 400'000'000;
};

Result<Raster> readGeoTiff(const std::filesystem::path& path, const ReadOptions& options = {});

}  // namespace vegstream::datasets
