// SourceGrid and the bilinear samplers (source_grid.h): the geometric half of reprojecting a
// GeoTIFF onto XYZ tiles.

#include "datasets/source_grid.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "datasets/message.h"
#include "geo/local_frame.h"
#include "geo/projection.h"

namespace vegstream::datasets {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

glm::dvec2 applyAffine(const std::array<double, 6>& t, glm::dvec2 p) {
  return {t[0] + t[1] * p.x + t[2] * p.y, t[3] + t[4] * p.x + t[5] * p.y};
}

// Clamps a continuous pixel coordinate c (corner-based) to the sample-centre range; returns
// false when it lies outside the raster's area.
bool edgeClamp(double& c, int n) {
  if (!(c >= 0.0 && c <= n)) return false;
  c = std::clamp(c - 0.5, 0.0, static_cast<double>(n - 1));
  return true;
}

// Bilinear between sample centres of r around pixel, over the valid of the four samples
// (valid(col, row)): add(col, row, weight) for each valid one; returns the weight of those
// (0 outside the raster).
template <class Valid, class Add>
double bilinearOverValid(const Raster& r, glm::dvec2 pixel, Valid&& valid, Add&& add) {
  const glm::dvec2 l = r.local(pixel);
  double c = l.x, w = l.y;
  if (!edgeClamp(c, r.width) || !edgeClamp(w, r.height)) return 0.0;
  const int c0 = std::min(static_cast<int>(c), std::max(r.width - 2, 0));
  const int r0 = std::min(static_cast<int>(w), std::max(r.height - 2, 0));
  const int c1 = std::min(c0 + 1, r.width - 1), r1 = std::min(r0 + 1, r.height - 1);
  const double fx = c - c0, fy = w - r0;
  const int cols[4] = {c0, c1, c0, c1}, rows[4] = {r0, r0, r1, r1};
  const double weights[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
  double wsum = 0;
  for (int k = 0; k < 4; ++k) {
    if (!valid(cols[k], rows[k])) continue;
    add(cols[k], rows[k], weights[k]);
    wsum += weights[k];
  }
  return wsum;
}

}  // namespace

bool extentsOverlap(const geo::GeoBounds& a, const geo::GeoBounds& b) {
  return a.westDeg < b.eastDeg && b.westDeg < a.eastDeg && a.southDeg < b.northDeg && b.southDeg < a.northDeg;
}

std::string extentText(const geo::GeoBounds& b) {
  char buf[160];
  std::snprintf(buf, sizeof(buf), "lon %.4f … %.4f, lat %.4f … %.4f", b.westDeg, b.eastDeg, b.southDeg, b.northDeg);
  return buf;
}

Result<GriddedSource> openGridded(const std::string& file, const SourceOptions& options) {
  auto source = RasterSource::open({file}, options);
  if (!source) return source.error();
  GriddedSource out{std::make_shared<RasterSource>(std::move(*source)), nullptr};
  auto grid = SourceGrid::make(*out.source);
  if (!grid) return grid.error();
  out.grid = std::make_shared<SourceGrid>(std::move(*grid));
  return out;
}

Result<SourceGrid> SourceGrid::make(const RasterSource& source) {
  SourceGrid g;
  g.source_ = &source;
  g.crs_ = source.crs();
  const geo::Crs& crs = g.crs_;
  const std::string& path = source.label();
  const auto& t = source.georef().transform;
  const double det = t[1] * t[5] - t[2] * t[4];
  if (!(std::abs(det) > 0.0) || !std::isfinite(det))
    return makeError(ErrorKind::InvalidInput, concat(path, " has a degenerate georeference (zero pixel size)"));
  // Inverse of [[t1 t2] [t4 t5]] applied to (x − t0, y − t3).
  const double ia = t[5] / det, ib = -t[2] / det, ic = -t[4] / det, id = t[1] / det;
  g.inverse_ = {ia, ib, ic, id, t[0], t[3]};

  // Densified boundary → lon/lat box.
  double west = 1e9, east = -1e9, south = 1e9, north = -1e9;
  constexpr int kSteps = 64;
  const double w = source.width(), h = source.height();
  for (int s = 0; s <= kSteps; ++s) {
    const double f = static_cast<double>(s) / kSteps;
    for (glm::dvec2 px : {glm::dvec2{f * w, 0.0}, glm::dvec2{f * w, h}, glm::dvec2{0.0, f * h}, glm::dvec2{w, f * h}}) {
      const geo::Geodetic p = geo::fromProjected(crs, applyAffine(t, px));
      if (!std::isfinite(p.latDeg) || !std::isfinite(p.lonDeg) || std::abs(p.latDeg) > 90.0 + 1e-9)
        return makeError(ErrorKind::InvalidInput,
                         concat(path, " has a georeference outside the earth in ", crs.name(),
                                " (check its CRS; a wrong --dem-crs / --imagery-crs does this)"));
      west = std::min(west, p.lonDeg);
      east = std::max(east, p.lonDeg);
      south = std::min(south, p.latDeg);
      north = std::max(north, p.latDeg);
    }
  }
  if (west < -180.0 - 1e-9 || east > 180.0 + 1e-9)
    return makeError(
        ErrorKind::Unsupported,
        concat(path, " reaches beyond ±180° longitude; rasters across the antimeridian are not supported"));
  const double lim = geo::kWebMercatorMaxLatDeg;
  g.extent_ = {std::max(west, -180.0), std::clamp(south, -lim, lim), std::min(east, 180.0),
               std::clamp(north, -lim, lim)};
  if (!(g.extent_.northDeg > g.extent_.southDeg))
    return makeError(ErrorKind::Unsupported,
                     concat(path, " lies entirely beyond ±85.05° latitude, outside Web Mercator"));

  // Ground pixel size at the centre, in a local ENU frame there.
  const glm::dvec2 c{0.5 * w, 0.5 * h};
  const geo::Geodetic p0 = geo::fromProjected(crs, applyAffine(t, c));
  const geo::LocalFrame frame(p0);
  const auto enu = [&](glm::dvec2 px) { return frame.toLocal(geo::fromProjected(crs, applyAffine(t, px))); };
  const auto ex = enu(c + glm::dvec2{1.0, 0.0}), ey = enu(c + glm::dvec2{0.0, 1.0});
  g.pixelSizeM_ = std::min(std::hypot(ex.x, ex.y), std::hypot(ey.x, ey.y));
  if (!(g.pixelSizeM_ > 0.0)) return makeError(ErrorKind::InvalidInput, concat(path, " has a zero ground pixel size"));
  return g;
}

glm::dvec2 SourceGrid::toPixel(glm::dvec2 xy) const {
  const double dx = xy.x - inverse_[4], dy = xy.y - inverse_[5];
  return {inverse_[0] * dx + inverse_[1] * dy, inverse_[2] * dx + inverse_[3] * dy};
}

std::vector<glm::dvec2> SourceGrid::tilePixelsToSource(const geo::TileId& tile, int size) const {
  const size_t n = static_cast<size_t>(size);
  std::vector<glm::dvec2> out(n * n);
  const auto centre = [&](double i, double j) { return glm::dvec2{i + 0.5, j + 0.5}; };
  if (crs_.isWgs84LonLat() || crs_.isWebMercator()) {
    // x depends on the column only, y on the row only.
    const bool merc = crs_.isWebMercator();
    std::vector<double> xs(n), ys(n);
    for (size_t i = 0; i < n; ++i) {
      const double d = static_cast<double>(i);
      xs[i] = merc ? geo::pixelToMercator(tile, centre(d, 0), size).x : geo::pixelToLonLat(tile, centre(d, 0), size).x;
      ys[i] = merc ? geo::pixelToMercator(tile, centre(0, d), size).y : geo::pixelToLonLat(tile, centre(0, d), size).y;
    }
    for (size_t j = 0; j < n; ++j)
      for (size_t i = 0; i < n; ++i) out[j * n + i] = toPixel({xs[i], ys[j]});
    return out;
  }
  constexpr int kStep = 8;
  const int cells = (size + kStep - 1) / kStep;
  const size_t gn = static_cast<size_t>(cells + 1);
  std::vector<glm::dvec2> grid(gn * gn);
  for (size_t gj = 0; gj < gn; ++gj)
    for (size_t gi = 0; gi < gn; ++gi) {
      const glm::dvec2 lonLat =
          geo::pixelToLonLat(tile, centre(static_cast<double>(gi * kStep), static_cast<double>(gj * kStep)), size);
      auto xy = geo::toProjected(crs_, {lonLat.y, lonLat.x, 0.0});
      grid[gj * gn + gi] = xy ? toPixel(*xy) : glm::dvec2{kNaN, kNaN};
    }
  for (size_t j = 0; j < n; ++j) {
    const size_t gj = j / kStep;
    const double fy = static_cast<double>(j % kStep) / kStep;
    for (size_t i = 0; i < n; ++i) {
      const size_t gi = i / kStep;
      const double fx = static_cast<double>(i % kStep) / kStep;
      const glm::dvec2 a = grid[gj * gn + gi], b = grid[gj * gn + gi + 1];
      const glm::dvec2 c = grid[(gj + 1) * gn + gi], d = grid[(gj + 1) * gn + gi + 1];
      out[j * n + i] = (a * (1 - fx) + b * fx) * (1 - fy) + (c * (1 - fx) + d * fx) * fy;
    }
  }
  return out;
}

Result<std::optional<Raster>> SourceGrid::windowFor(const std::vector<glm::dvec2>& pixels, int margin,
                                                    int maxSide) const {
  double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
  const double w = source_->width(), h = source_->height();
  for (const glm::dvec2& p : pixels) {
    if (!(p.x >= 0.0 && p.x <= w && p.y >= 0.0 && p.y <= h)) continue;  // NaN too
    x0 = std::min(x0, p.x);
    y0 = std::min(y0, p.y);
    x1 = std::max(x1, p.x);
    y1 = std::max(y1, p.y);
  }
  if (!(x0 <= x1)) return std::optional<Raster>();
  const int c0 = static_cast<int>(std::floor(x0 - 0.5)) - margin, r0 = static_cast<int>(std::floor(y0 - 0.5)) - margin;
  const int c1 = static_cast<int>(std::floor(x1 - 0.5)) + 2 + margin,
            r1 = static_cast<int>(std::floor(y1 - 0.5)) + 2 + margin;
  const int cx = std::max(c0, 0), cy = std::max(r0, 0);
  auto r = source_->read(cx, cy, std::min(c1, source_->width()) - cx, std::min(r1, source_->height()) - cy, maxSide);
  if (!r) return r.error();
  return std::optional<Raster>(std::move(*r));
}

float sampleHeight(const Raster& r, glm::dvec2 pixel) {
  const glm::dvec2 l = r.local(pixel);
  double c = l.x, w = l.y;
  if (!edgeClamp(c, r.width) || !edgeClamp(w, r.height)) return NAN;
  const int c0 = std::min(static_cast<int>(c), std::max(r.width - 2, 0));
  const int r0 = std::min(static_cast<int>(w), std::max(r.height - 2, 0));
  const int c1 = std::min(c0 + 1, r.width - 1), r1 = std::min(r0 + 1, r.height - 1);
  const double fx = c - c0, fy = w - r0;
  const float v00 = r.at(c0, r0), v10 = r.at(c1, r0), v01 = r.at(c0, r1), v11 = r.at(c1, r1);
  if (r.isNodata(v00) || r.isNodata(v10) || r.isNodata(v01) || r.isNodata(v11)) return NAN;
  return static_cast<float>((v00 * (1 - fx) + v10 * fx) * (1 - fy) + (v01 * (1 - fx) + v11 * fx) * fy);
}

float sampleHeightCubic(const Raster& r, glm::dvec2 pixel) {
  const glm::dvec2 l = r.local(pixel);
  const double c = l.x - 0.5, w = l.y - 0.5;  // in sample-centre units
  if (!(c >= 1.0 && w >= 1.0 && c < r.width - 2.0 && w < r.height - 2.0)) return sampleHeight(r, pixel);
  const int c0 = static_cast<int>(c), r0 = static_cast<int>(w);
  const double fx = c - c0, fy = w - r0;
  // Catmull-Rom weights for offsets −1, 0, 1, 2.
  const auto weights = [](double t, double out[4]) {
    const double t2 = t * t, t3 = t2 * t;
    out[0] = 0.5 * (-t3 + 2 * t2 - t);
    out[1] = 0.5 * (3 * t3 - 5 * t2 + 2);
    out[2] = 0.5 * (-3 * t3 + 4 * t2 + t);
    out[3] = 0.5 * (t3 - t2);
  };
  double wx[4], wy[4];
  weights(fx, wx);
  weights(fy, wy);
  double sum = 0.0;
  for (int dy = 0; dy < 4; ++dy) {
    double rowSum = 0.0;
    for (int dx = 0; dx < 4; ++dx) {
      const float v = r.at(c0 - 1 + dx, r0 - 1 + dy);
      if (r.isNodata(v)) return NAN;
      rowSum += wx[dx] * v;
    }
    sum += wy[dy] * rowSum;
  }
  const float v00 = r.at(c0, r0), v10 = r.at(c0 + 1, r0), v01 = r.at(c0, r0 + 1), v11 = r.at(c0 + 1, r0 + 1);
  const double lo = std::min(std::min(v00, v10), std::min(v01, v11));
  const double hi = std::max(std::max(v00, v10), std::max(v01, v11));
  return static_cast<float>(std::clamp(sum, lo, hi));
}

bool sampleColour(const Raster& r, glm::dvec2 pixel, std::array<float, 3>& rgb) {
  double sum[3] = {0, 0, 0};
  const double wsum = bilinearOverValid(
      r, pixel, [&](int col, int row) { return !std::isnan(r.at(col, row, 0)); },
      [&](int col, int row, double weight) {
        for (int ch = 0; ch < 3; ++ch) sum[ch] += weight * r.at(col, row, ch);
      });
  if (wsum < 0.5) return false;
  for (int ch = 0; ch < 3; ++ch) rgb[static_cast<size_t>(ch)] = static_cast<float>(sum[ch] / wsum);
  return true;
}

float sampleValue(const Raster& r, glm::dvec2 pixel) {
  double sum = 0;
  const double wsum = bilinearOverValid(
      r, pixel, [&](int col, int row) { return !r.isNodata(r.at(col, row)); },
      [&](int col, int row, double weight) { sum += weight * r.at(col, row); });
  return wsum < 0.5 ? NAN : static_cast<float>(sum / wsum);
}

}  // namespace vegstream::datasets
