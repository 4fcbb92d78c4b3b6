// The ground the trees read (tree_ground.h): mosaics of heights, imagery and NDVI sampled at
// local ENU points for the tree placement (core seed ../shared/seeds/001_3eca9f2c7752e4fb.txt
// §3.3: species from the imagery colour under the seed).
#include "scene/tree_ground.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>

#include "geo/projection.h"
#include "vegetation/colour_score.h"

namespace vegstream::scene {

struct TreeGround::Data {
  streaming::HeightMosaic heights;
  streaming::ImageryMosaic imagery;
  geo::LocalFrame frame;
  std::array<float, 256> linear{};  // sRGB byte → linear, vegetation::srgbDecode's values

  // The four pixels around a point and its weights; false outside the pixel centres.
  struct Footprint {
    size_t i00, i10, i01, i11;
    double fx, fy;
  };
  bool footprint(const geo::Geodetic& at, Footprint& f) const {
    const glm::dvec2 m = geo::lonLatToWebMercator({at.lonDeg, at.latDeg});
    const double col = (m.x - heights.x0) / heights.pixelM, row = (heights.y0 - m.y) / heights.pixelM;
    const int w = heights.width, h = heights.height;
    if (w < 2 || h < 2 || !(col >= 0.0 && row >= 0.0 && col <= w - 1 && row <= h - 1)) return false;
    // On the last column or row the pair before it, with weight 1 on the last.
    const int c0 = std::min(static_cast<int>(col), w - 2), r0 = std::min(static_cast<int>(row), h - 2);
    const size_t i00 = static_cast<size_t>(r0) * static_cast<size_t>(w) + static_cast<size_t>(c0);
    const size_t i01 = i00 + static_cast<size_t>(w);
    f = {i00, i00 + 1, i01, i01 + 1, col - c0, row - r0};
    return true;
  }

  // Bilinear height, NaN where one of the four has none.
  double heightAt(const Footprint& f) const {
    const std::vector<float>& h = heights.heights;
    const double top = h[f.i00] + (h[f.i10] - double(h[f.i00])) * f.fx;
    const double bottom = h[f.i01] + (h[f.i11] - double(h[f.i01])) * f.fx;
    return top + (bottom - top) * f.fy;
  }

  // Bilinear height at pixel coordinates (col, row); NaN outside the mosaic or where one of the
  // four has none.
  double heightAtPixel(double col, double row) const {
    const int w = heights.width, h = heights.height;
    if (!(col >= 0.0 && row >= 0.0 && col <= w - 1 && row <= h - 1)) return NAN;
    const int c0 = std::min(static_cast<int>(col), w - 2), r0 = std::min(static_cast<int>(row), h - 2);
    const size_t i00 = static_cast<size_t>(r0) * static_cast<size_t>(w) + static_cast<size_t>(c0);
    return heightAt({i00, i00 + 1, i00 + static_cast<size_t>(w), i00 + static_cast<size_t>(w) + 1, col - c0, row - r0});
  }

  // The site at pixel (col, row) of height h at latitude latDeg (vegetation/tree_niche.h): the
  // slope by central differences over a pixel each way, the relief against 8 points of a ring of
  // kReliefRadiusM (NaN where the mosaic does not reach).
  vegetation::TreeSite siteAt(double col, double row, double h, double latDeg) const {
    vegetation::TreeSite site;
    site.elevationM = static_cast<float>(h);
    const double groundPixelM = heights.pixelM * std::cos(latDeg * 3.14159265358979323846 / 180.0);
    const double dx = heightAtPixel(col + 1.0, row) - heightAtPixel(col - 1.0, row);
    const double dy = heightAtPixel(col, row + 1.0) - heightAtPixel(col, row - 1.0);
    const double grad = std::hypot(dx, dy) / (2.0 * groundPixelM);
    if (std::isfinite(grad)) site.slopeDeg = static_cast<float>(std::atan(grad) * 180.0 / 3.14159265358979323846);
    const double r = vegetation::kReliefRadiusM / groundPixelM;
    double ring = 0.0;
    for (int k = 0; k < 8; ++k) {
      const double a = k * 3.14159265358979323846 / 4.0;
      ring += heightAtPixel(col + r * std::cos(a), row + r * std::sin(a));
    }
    if (std::isfinite(ring)) site.reliefM = static_cast<float>(h - ring / 8.0);
    return site;
  }
};

streaming::SnapshotLimits TreeGround::defaultLimits() {
  streaming::SnapshotLimits limits;
  limits.maxHeightPixels = kDefaultMaxPixels;
  return limits;
}

TreeGround::TreeGround(streaming::HeightMosaic heights, streaming::ImageryMosaic imagery, const geo::LocalFrame& frame) {
  assert(imagery.width == heights.width && imagery.height == heights.height && imagery.zoom == heights.zoom);
  assert(imagery.rgba.size() == heights.heights.size() * 4);
  auto d = std::make_shared<Data>(Data{std::move(heights), std::move(imagery), frame, {}});
  for (int i = 0; i < 256; ++i) d->linear[static_cast<size_t>(i)] = vegetation::srgbDecode(static_cast<float>(i) / 255.0f);
  data_ = std::move(d);
}

Result<TreeGround> TreeGround::load(streaming::TileSource& source, const datasets::DatasetMeta& meta,
                                    const geo::LocalFrame& frame, const streaming::SnapshotLimits& limits) {
  auto heights = streaming::loadGroundHeights(source, meta, limits);
  if (!heights) return heights.error();
  auto imagery = streaming::loadGroundImagery(source, meta, *heights, limits);
  if (!imagery) return imagery.error();
  return TreeGround(std::move(*heights), std::move(*imagery), frame);
}

vegetation::TreeGroundSample TreeGround::sample(double x, double y) const {
  const Data& d = *data_;
  vegetation::TreeGroundSample out;
  // The ground point seen at (x, y): first at the frame's z = 0, then at the ground's z there.
  Data::Footprint f{};
  geo::Geodetic at = d.frame.toGeodetic({x, y, 0.0});
  if (!d.footprint(at, f)) return out;
  double h = d.heightAt(f);
  if (!std::isfinite(h)) return out;
  const double z = d.frame.toLocal({at.latDeg, at.lonDeg, h}).z;
  at = d.frame.toGeodetic({x, y, z});
  if (!d.footprint(at, f)) return out;
  h = d.heightAt(f);
  if (!std::isfinite(h)) return out;

  const uint8_t* rgba = d.imagery.rgba.data();
  const size_t corners[4] = {f.i00, f.i10, f.i01, f.i11};
  const double weights[4] = {(1 - f.fx) * (1 - f.fy), f.fx * (1 - f.fy), (1 - f.fx) * f.fy, f.fx * f.fy};
  glm::vec3 colour(0.0f);
  for (int k = 0; k < 4; ++k) {
    const uint8_t* p = rgba + 4 * corners[k];
    if (p[3] == 0) return out;  // no imagery under one of the four
    colour += static_cast<float>(weights[k]) * glm::vec3(d.linear[p[0]], d.linear[p[1]], d.linear[p[2]]);
  }
  float ndvi = vegetation::kNoNdvi;
  if (!d.imagery.ndvi.empty()) {
    double sum = 0.0, weight = 0.0;
    for (int k = 0; k < 4; ++k) {
      const uint8_t b = d.imagery.ndvi[corners[k]];
      if (b == 0) continue;
      sum += weights[k] * ((static_cast<double>(b) - 128.0) / 127.0);
      weight += weights[k];
    }
    if (weight > 0.0) ndvi = static_cast<float>(sum / weight);
  }
  if (masks_ && !d.imagery.landcover.empty()) {
    // The nearest pixel: the corner whose square holds the point (weights of 0.5 to the later).
    const size_t cls = f.fy < 0.5 ? (f.fx < 0.5 ? f.i00 : f.i10) : (f.fx < 0.5 ? f.i01 : f.i11);
    out.allowed = (*masks_)[d.imagery.landcover[cls]];
  }
  out.valid = true;
  out.linearRgb = colour;
  out.ndvi = ndvi;
  out.heightM = d.frame.toLocal({at.latDeg, at.lonDeg, h}).z;
  out.site = d.siteAt(double(f.i00 % size_t(d.heights.width)) + f.fx, double(f.i00 / size_t(d.heights.width)) + f.fy, h,
                      at.latDeg);
  return out;
}

void TreeGround::allowLandcover(const LandcoverMasks& masks) { masks_ = std::make_shared<const LandcoverMasks>(masks); }

vegetation::TreeGroundAt TreeGround::at() const {
  // A copy sharing the mosaics: valid however long the callback lives.
  return [ground = *this](double x, double y) { return ground.sample(x, y); };
}

int TreeGround::zoom() const { return data_->heights.zoom; }
double TreeGround::pixelM() const { return data_->heights.pixelM; }
size_t TreeGround::bytes() const {
  return data_->heights.heights.size() * sizeof(float) + data_->imagery.rgba.size() + data_->imagery.ndvi.size() +
         data_->imagery.landcover.size();
}

}  // namespace vegstream::scene
