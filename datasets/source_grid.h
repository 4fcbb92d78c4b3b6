#pragma once
// A source raster placed on the earth: its CRS, the inverse of its GeoReference affine, its
// extent in longitude/latitude and its ground pixel size; the window of it a tile needs; plus
// the samplers the importer uses to reproject it onto XYZ tiles. All projection goes through
// geo/ (PROJ).
//
// Pixel coordinates here are continuous and corner-based in the whole raster, as in
// GeoReference: the centre of pixel (i, j) is (i + 0.5, j + 0.5). The samplers take them so and
// read the window they are given (Raster::local), which must hold every sample they touch: a
// window from windowFor() does.

#include <array>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "core/log.h"
#include "core/result.h"
#include "datasets/raster.h"
#include "datasets/raster_source.h"
#include "geo/bounds.h"
#include "geo/crs.h"
#include "geo/xyz_tiles.h"

namespace vegstream::datasets {

// Whether two longitude/latitude boxes share an area, and one printed for messages
// ("lon -113.2396 … -112.8521, lat 37.1321 … 37.5129").
bool extentsOverlap(const geo::GeoBounds& a, const geo::GeoBounds& b);
std::string extentText(const geo::GeoBounds& b);

class SourceGrid {
 public:
  // Errors: a degenerate (non-invertible) transform, a raster whose corners do not map to
  // valid latitudes. Messages name the raster's file. `source` outlives the grid.
  static Result<SourceGrid> make(const RasterSource& source);

  const RasterSource& source() const { return *source_; }
  const geo::Crs& crs() const { return crs_; }
  // CRS coordinates → continuous pixel coordinates (corner-based).
  glm::dvec2 toPixel(glm::dvec2 xy) const;
  // Longitude/latitude box of the raster's area (its boundary densified, so a UTM raster's
  // curved edges are enclosed), latitudes clamped to the Web Mercator range.
  const geo::GeoBounds& extent() const { return extent_; }
  // Ground size of one pixel at the raster's centre, metres: the finer of east-west and
  // north-south (measured in a local ENU frame).
  double pixelSizeM() const { return pixelSizeM_; }

  // Source pixel coordinates of the centres of every pixel of an XYZ tile (row-major from the
  // north, size × size). Geographic and Web Mercator sources are separable and computed
  // exactly; other CRSs are projected exactly on a grid every 8 pixels and interpolated
  // bilinearly in between (as GDAL's approximate transformer does: far below 0.01 pixel for
  // UTM at any zoom a raster needs). Pixels whose position cannot be projected are NaN.
  std::vector<glm::dvec2> tilePixelsToSource(const geo::TileId& tile, int size) const;

  // The window of the raster that sampling at `pixels` needs (their bounding box, `margin`
  // samples more on every side — 2 for the cubic sampler — clamped to the raster), read through
  // the source, decimated when it would exceed maxSide pixels on a side. nullopt when no
  // position falls on the raster. Errors: the source's read errors.
  Result<std::optional<Raster>> windowFor(const std::vector<glm::dvec2>& pixels, int margin, int maxSide) const;

 private:
  const RasterSource* source_ = nullptr;
  geo::Crs crs_;
  std::array<double, 6> inverse_{};
  geo::GeoBounds extent_;
  double pixelSizeM_ = 0.0;
};

// A raster source and its grid, both shared: the grid points into the source, so the two move
// and copy as one (the landcover, canopy-height and near-infrared layers keep them so).
struct GriddedSource {
  std::shared_ptr<RasterSource> source;
  std::shared_ptr<SourceGrid> grid;
};
// `file` opened with `options`, and its grid (the errors of RasterSource::open and
// SourceGrid::make).
Result<GriddedSource> openGridded(const std::string& file, const SourceOptions& options);

// Samplers: `pixel` in whole-raster coordinates, `raster` a window holding the samples around it.
//
// Bilinear height at continuous pixel coordinates: NaN when outside the raster or when any of
// the four neighbours is nodata (a mask never becomes a fake height). Within half a pixel of
// the raster's edge the edge row/column is used, so the raster's whole area is covered.
float sampleHeight(const Raster& raster, glm::dvec2 pixel);

// Catmull-Rom bicubic height (interpolates the samples like bilinear, but C1: no kinks at the
// source pixel centres), clamped to the range of the four nearest samples so it never
// overshoots a summit or a valley floor. NaN when any of the 16 samples is nodata or outside.
// Within half a pixel of the raster's edge: bilinear.
float sampleHeightCubic(const Raster& raster, glm::dvec2 pixel);

// Bilinear colour of a 3-channel raster holding 0 … 255 with NaN for nodata: the weights of the
// valid neighbours are renormalised; false (no colour) when less than half the weight is valid.
bool sampleColour(const Raster& raster, glm::dvec2 pixel, std::array<float, 3>& rgb);

// The same for a one-channel raster whose nodata is NaN or its nodata value (Raster::isNodata):
// NaN when less than half the weight is valid.
float sampleValue(const Raster& raster, glm::dvec2 pixel);

}  // namespace vegstream::datasets
