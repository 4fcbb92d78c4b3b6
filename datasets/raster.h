#pragma once
// A block of a georeferenced raster in memory: what raster_source.h reads out of a file through
// GDAL, one window at a time, and what the importer's samplers (source_grid.h) read from.
//
// Pixel coordinates are continuous and corner-based in the *whole* raster: (0, 0) is the
// top-left corner of the first pixel, the centre of pixel (i, j) is (i + 0.5, j + 0.5). A
// window holds the pixels from `origin` on, each buffer pixel standing for `step` × `step`
// source pixels when the window was read decimated (step 1: the file's own pixels).

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "geo/crs.h"

namespace vegstream::datasets {

struct GeoReference {
  std::optional<geo::Crs> crs;  // none: the file names no CRS (the user must state one)
  std::string crsDescription;   // what the file says, for messages
  // Affine map from continuous pixel coordinates (col, row) of the whole raster, (0, 0) the
  // top-left *corner* of the first pixel, to CRS coordinates (GDAL's geotransform):
  //   x = t[0] + t[1]·col + t[2]·row,   y = t[3] + t[4]·col + t[5]·row
  std::array<double, 6> transform{0, 1, 0, 0, 0, -1};

  // CRS coordinates of the centre of pixel (col, row).
  std::array<double, 2> pixelCentre(double col, double row) const {
    const double c = col + 0.5, r = row + 0.5;
    return {transform[0] + transform[1] * c + transform[2] * r, transform[3] + transform[4] * c + transform[5] * r};
  }
};

struct Raster {
  std::string path;  // the file or URL, for messages
  int width = 0;     // of this block, in buffer pixels
  int height = 0;
  int channels = 0;
  std::vector<float> samples;    // row-major from the top row, channels interleaved; NaN = no data
  std::optional<double> nodata;  // a value that also means no data (besides NaN)
  GeoReference georef;           // of the whole raster
  glm::dvec2 origin{0.0, 0.0};   // whole-raster pixel coordinates of this block's top-left corner
  glm::dvec2 step{1.0, 1.0};     // whole-raster pixels per buffer pixel

  float at(int col, int row, int channel = 0) const {
    return samples[(static_cast<size_t>(row) * static_cast<size_t>(width) + static_cast<size_t>(col)) *
                       static_cast<size_t>(channels) +
                   static_cast<size_t>(channel)];
  }
  bool isNodata(float v) const { return v != v || (nodata && static_cast<double>(v) == *nodata); }
  // Whole-raster pixel coordinates → this block's buffer coordinates (what the samplers take).
  glm::dvec2 local(glm::dvec2 pixel) const { return (pixel - origin) / step; }
};

}  // namespace vegstream::datasets
