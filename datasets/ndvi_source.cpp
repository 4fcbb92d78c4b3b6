// NDVI of an import with --imagery-nir / --nir-band (ndvi_source.h): the near-infrared band
// opened and checked, reprojected onto each imagery window's pixel centres, and combined with
// the window's raw red.

#include "datasets/ndvi_source.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "datasets/message.h"
#include "geo/projection.h"

namespace vegstream::datasets {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Exact projections every kStep imagery pixels, bilinear in between: the same trade as
// SourceGrid::tilePixelsToSource (far below 0.01 pixel for UTM ↔ geographic at 30 m pixels).
constexpr int kStep = 8;

bool sameGrid(const RasterSource& a, const RasterSource& b) {
  return a.width() == b.width() && a.height() == b.height() && a.crs() == b.crs() &&
         a.georef().transform == b.georef().transform;
}

std::string describe(const RasterSource& nir, const SourceGrid& grid, bool sameGridAsImagery) {
  char buf[256];
  std::snprintf(buf, sizeof(buf),
                "%s, %.2f m pixels; near-infrared for NDVI with the imagery's red before the stretch%s",
                nir.description().c_str(), grid.pixelSizeM(),
                sameGridAsImagery ? ", same grid" : ", reprojected onto the imagery's grid");
  return buf;
}

}  // namespace

float ndviOf(float nir, float red) {
  const float sum = nir + red;
  if (!(sum > 0.0f)) return NAN;  // NaN in either, or no positive total to divide by
  return std::clamp((nir - red) / sum, -1.0f, 1.0f);
}

Result<NdviSource> NdviSource::open(const NirInput& in, const SourceGrid& imagery, const Logger& log) {
  auto opened = openGridded(
      in.file,
      {.flag = "--imagery-nir", .crsFlag = "--imagery-nir-crs", .assumeCrs = in.assumeCrs, .bands = {in.band}});
  if (!opened) return opened.error();
  NdviSource out;
  out.nir_ = opened->source;
  out.grid_ = opened->grid;
  if (!extentsOverlap(out.grid_->extent(), imagery.extent()))
    return makeError(
        ErrorKind::InvalidInput,
        concat("the near-infrared file ", in.file, " (", extentText(out.grid_->extent()), ") and the imagery ",
               imagery.source().label(), " (", extentText(imagery.extent()), ") do not overlap"));
  out.imagery_ = &imagery;
  out.sameGrid_ = sameGrid(imagery.source(), *out.nir_);
  out.description_ = describe(*out.nir_, *out.grid_, out.sameGrid_);
  log->info("{}: band {}, {} ({:.1f} m pixels), NDVI with the imagery's red", in.file, in.band, out.nir_->crs().name(),
            out.grid_->pixelSizeM());
  return out;
}

// NIR pixel coordinates of the window's pixel centres: exact on nodes every kStep pixels of the
// whole imagery's grid (of the window's buffer when it was decimated), bilinear in between.
std::vector<glm::dvec2> NdviSource::nirPositions(const Raster& w) const {
  const bool whole = w.step == glm::dvec2(1.0, 1.0);
  const int ox = whole ? static_cast<int>(w.origin.x) : 0, oy = whole ? static_cast<int>(w.origin.y) : 0;
  const int gx0 = ox / kStep, gy0 = oy / kStep;
  const int cols = (ox + w.width) / kStep - gx0 + 2, rows = (oy + w.height) / kStep - gy0 + 2;
  const GeoReference& g = imagery_->source().georef();
  std::vector<glm::dvec2> nodes(static_cast<size_t>(cols) * static_cast<size_t>(rows));
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < cols; ++i) {
      // node (i, j) is buffer pixel ((gx0 + i)·kStep − ox, …); its whole-raster centre:
      const double bx = (gx0 + i) * kStep - ox + 0.5, by = (gy0 + j) * kStep - oy + 0.5;
      const glm::dvec2 px = w.origin + glm::dvec2(bx, by) * w.step - glm::dvec2(0.5);
      const auto xy = g.pixelCentre(px.x, px.y);
      const geo::Geodetic p = geo::fromProjected(imagery_->crs(), {xy[0], xy[1]});
      auto to = geo::toProjected(grid_->crs(), p);
      nodes[static_cast<size_t>(j * cols + i)] = to ? grid_->toPixel(*to) : glm::dvec2{kNaN, kNaN};
    }
  std::vector<glm::dvec2> out(static_cast<size_t>(w.width) * static_cast<size_t>(w.height));
  for (int y = 0; y < w.height; ++y)
    for (int x = 0; x < w.width; ++x) {
      const int gx = ox + x, gy = oy + y;
      const int i = gx / kStep - gx0, j = gy / kStep - gy0;
      const double fx = static_cast<double>(gx % kStep) / kStep, fy = static_cast<double>(gy % kStep) / kStep;
      const auto at = [&](int a, int b) { return nodes[static_cast<size_t>(b * cols + a)]; };
      out[static_cast<size_t>(y * w.width + x)] =
          (at(i, j) * (1 - fx) + at(i + 1, j) * fx) * (1 - fy) + (at(i, j + 1) * (1 - fx) + at(i + 1, j + 1) * fx) * fy;
    }
  return out;
}

Result<Raster> NdviSource::ndviFor(const ImageryWindow& w, int maxSide) const {
  const Raster& c = w.colour;
  Raster out = c;
  out.channels = 1;
  out.nodata.reset();
  const size_t count = static_cast<size_t>(c.width) * static_cast<size_t>(c.height);
  out.samples.assign(count, NAN);
  if (sameGrid_) {
    const int ww = static_cast<int>(std::lround(c.width * c.step.x)),
              wh = static_cast<int>(std::lround(c.height * c.step.y));
    auto nir = nir_->read(static_cast<int>(c.origin.x), static_cast<int>(c.origin.y), ww, wh, maxSide);
    if (!nir) return nir.error();
    assert(nir->width == c.width && nir->height == c.height);
    for (size_t p = 0; p < count; ++p) out.samples[p] = ndviOf(nir->samples[p], w.rawRed[p]);
    return out;
  }
  const std::vector<glm::dvec2> positions = nirPositions(c);
  auto window = grid_->windowFor(positions, 1, 0);
  if (!window) return window.error();
  if (!*window) return out;
  for (size_t p = 0; p < count; ++p) {
    if (std::isnan(w.rawRed[p])) continue;
    out.samples[p] = ndviOf(sampleValue(**window, positions[p]), w.rawRed[p]);
  }
  return out;
}

}  // namespace vegstream::datasets
