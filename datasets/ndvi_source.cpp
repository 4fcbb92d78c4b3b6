// The NDVI raster of an import with --imagery-nir (ndvi_source.h): the near-infrared file read
// and checked, reprojected onto the imagery's pixel centres, and combined with the raw red.

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

bool sameGrid(const Raster& a, const geo::Crs& aCrs, const Raster& b, const geo::Crs& bCrs) {
  return a.width == b.width && a.height == b.height && aCrs == bCrs && a.georef.transform == b.georef.transform;
}

// NIR pixel coordinates (corner-based) of the imagery's pixel centres, on a coarse grid of
// exact projections: node (gi, gj) is imagery pixel (gi·kStep, gj·kStep).
class NirPositions {
 public:
  NirPositions(const SourceGrid& imagery, const SourceGrid& nir) {
    const Raster& r = imagery.raster();
    cols_ = r.width / kStep + 2;
    const int rows = r.height / kStep + 2;
    nodes_.resize(static_cast<size_t>(cols_) * static_cast<size_t>(rows));
    for (int gj = 0; gj < rows; ++gj)
      for (int gi = 0; gi < cols_; ++gi) {
        const auto xy = r.georef.pixelCentre(gi * kStep, gj * kStep);
        const geo::Geodetic p = geo::fromProjected(imagery.crs(), {xy[0], xy[1]});
        auto to = geo::toProjected(nir.crs(), p);
        nodes_[index(gi, gj)] = to ? nir.toPixel(*to) : glm::dvec2{kNaN, kNaN};
      }
  }

  glm::dvec2 at(int i, int j) const {
    const int gi = i / kStep, gj = j / kStep;
    const double fx = static_cast<double>(i % kStep) / kStep, fy = static_cast<double>(j % kStep) / kStep;
    const glm::dvec2 a = nodes_[index(gi, gj)], b = nodes_[index(gi + 1, gj)];
    const glm::dvec2 c = nodes_[index(gi, gj + 1)], d = nodes_[index(gi + 1, gj + 1)];
    return (a * (1 - fx) + b * fx) * (1 - fy) + (c * (1 - fx) + d * fx) * fy;
  }

 private:
  size_t index(int gi, int gj) const {
    return static_cast<size_t>(gj) * static_cast<size_t>(cols_) + static_cast<size_t>(gi);
  }
  int cols_ = 0;
  std::vector<glm::dvec2> nodes_;
};

std::string describe(const SourceGrid& nir, bool sameGridAsImagery, double coveredPercent) {
  char buf[256];
  std::snprintf(buf, sizeof(buf),
                "%dx%d px, %.2f m pixels; near-infrared for NDVI with the imagery's red before the stretch%s "
                "(NDVI on %.1f %% of the imagery's pixels)",
                nir.raster().width, nir.raster().height, nir.pixelSizeM(),
                sameGridAsImagery ? ", same grid" : ", reprojected onto the imagery's grid", coveredPercent);
  return buf;
}

}  // namespace

float ndviOf(float nir, float red) {
  const float sum = nir + red;
  if (!(sum > 0.0f)) return NAN;  // NaN in either, or no positive total to divide by
  return std::clamp((nir - red) / sum, -1.0f, 1.0f);
}

Result<NdviRaster> prepareNdvi(const NirInput& in, const SourceGrid& imagery, std::span<const float> rawRed,
                               const Logger& log) {
  const Raster& img = imagery.raster();
  const size_t count = static_cast<size_t>(img.width) * static_cast<size_t>(img.height);
  assert(rawRed.size() == count);

  ReadOptions ro;
  ro.assumeEpsg = in.assumeEpsg;
  ro.maxPixels = in.maxPixels;
  auto read = readGeoTiff(in.file, ro);
  if (!read) return read.error();
  const Raster& nir = *read;
  if (nir.channels != 1)
    return makeError(ErrorKind::InvalidInput, concat(in.file, " has ", nir.channels,
                                                     " bands; --imagery-nir takes one near-infrared band"));
  auto crs = rasterCrs(nir, "--imagery-nir-crs", log);
  if (!crs) return crs.error();
  auto grid = SourceGrid::make(nir, *crs);
  if (!grid) return grid.error();
  if (!extentsOverlap(grid->extent(), imagery.extent()))
    return makeError(ErrorKind::InvalidInput,
                     concat("the near-infrared file ", in.file, " (", extentText(grid->extent()), ") and the imagery ",
                            img.path, " (", extentText(imagery.extent()), ") do not overlap"));

  NdviRaster out;
  out.nirCrs = *crs;
  Raster& r = out.raster;
  r.path = in.file;
  r.width = img.width;
  r.height = img.height;
  r.channels = 1;
  r.georef = img.georef;
  r.samples.assign(count, NAN);

  const bool same = sameGrid(img, imagery.crs(), nir, *crs);
  std::optional<NirPositions> positions;
  if (!same) positions.emplace(imagery, *grid);
  size_t valid = 0;
  for (int j = 0; j < img.height; ++j)
    for (int i = 0; i < img.width; ++i) {
      const size_t p = static_cast<size_t>(j) * static_cast<size_t>(img.width) + static_cast<size_t>(i);
      if (std::isnan(rawRed[p])) continue;
      float v = NAN;
      if (same) {
        v = nir.at(i, j);
        if (nir.isNodata(v)) continue;
      } else {
        v = sampleValue(nir, positions->at(i, j));
      }
      r.samples[p] = ndviOf(v, rawRed[p]);
      valid += !std::isnan(r.samples[p]);
    }
  if (valid == 0)
    return makeError(ErrorKind::InvalidInput,
                     concat("the near-infrared file ", in.file, " gives no NDVI over the imagery ", img.path,
                            ": no pixel where both have data (or NIR + red > 0)"));
  const double percent = 100.0 * static_cast<double>(valid) / static_cast<double>(count);
  out.description = describe(*grid, same, percent);
  log->info("{}: {} ({:.1f} m pixels), NDVI on {:.1f} % of the imagery's pixels", in.file.string(), crs->name(),
            grid->pixelSizeM(), percent);
  return out;
}

}  // namespace vegstream::datasets
