#pragma once
// The Zion sample's ground colour over a nadir view's footprint, two ways, for the reflectance
// tests: from the Landsat bands themselves (issue 39's definition: DN × 2e-5 − 0.1, dark-object
// subtracted, linear mean, sRGB-encoded), and from an imported dataset's max-zoom imagery tiles
// (sRGB-decoded, linear mean). Computed here independently of the importer's code.

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "datasets/dataset_format.h"
#include "datasets/raster_source.h"
#include "datasets/tile_codec.h"
#include "geo/crs.h"
#include "geo/projection.h"
#include "geo/xyz_tiles.h"
#include <glm/geometric.hpp>
#include "tests/support/ciede2000.h"

namespace vegstream::datasets::test {

// The central half of a 320 × 180 nadir view from 300 m with a 55° vertical field of view:
// 2 · 300 · tan(27.5°) = 312 m north-south, 555 m east-west; half of each.
inline constexpr double kFootprintHalfNorthM = 78.0, kFootprintHalfEastM = 138.7;

struct Place {
  const char* name;
  double latDeg, lonDeg;
};

struct LinearRgb {
  std::array<double, 3> rgb{};
  int pixels = 0;
  std::array<int, 3> srgb8() const {
    std::array<int, 3> o{};
    for (size_t c = 0; c < 3; ++c)
      o[c] = static_cast<int>(std::lround(255.0 * vegstream::testing::linearToSrgb(std::clamp(rgb[c], 0.0, 1.0))));
    return o;
  }
  vegstream::testing::Lab lab() const { return vegstream::testing::labFromLinear(rgb[0], rgb[1], rgb[2]); }
};

inline double percentileOf(std::vector<double> v, double pct) {
  const size_t k = static_cast<size_t>(std::llround(pct / 100.0 * static_cast<double>(v.size() - 1)));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

// Bands 4, 3, 2 as surface reflectance: DN · 2e-5 − 0.1, less each band's haze (its 0.01th
// percentile over the pixels valid in all three bands, less 1 %), clamped to 0 … 1.
class LandsatReflectance {
 public:
  explicit LandsatReflectance(const std::string& zionDir) {
    for (int b = 0; b < 3; ++b) {
      auto r = readWholeRaster(zionDir + "/landsat_b" + std::to_string(4 - b) + ".tif");
      ok_ = ok_ && r.ok();
      if (r) bands_[static_cast<size_t>(b)] = std::move(*r);
    }
    if (!ok_) return;
    const Raster& r = bands_[0];
    for (size_t c = 0; c < 3; ++c) {
      std::vector<double> rho;
      for (int j = 0; j < r.height; ++j)
        for (int i = 0; i < r.width; ++i)
          if (valid(i, j)) rho.push_back(bands_[c].at(i, j) * 2e-5 - 0.1);
      haze_[c] = std::max(0.0, percentileOf(rho, 0.01) - 0.01);
    }
  }
  bool ok() const { return ok_; }
  const std::array<double, 3>& haze() const { return haze_; }

  // Mean over the Landsat pixels whose centres lie in the footprint around `p`.
  LinearRgb footprintMean(const Place& p) const {
    LinearRgb out;
    auto utm = Result<geo::Crs>(geo::utmCrs(12, true));
    auto centre =
        utm ? geo::toProjected(*utm, geo::Geodetic{p.latDeg, p.lonDeg, 0.0}) : Result<glm::dvec2>(utm.error());
    if (!centre) return out;
    const Raster& r = bands_[0];
    for (int j = 0; j < r.height; ++j)
      for (int i = 0; i < r.width; ++i) {
        const auto xy = r.georef.pixelCentre(i, j);
        if (std::abs(xy[0] - centre->x) > kFootprintHalfEastM || std::abs(xy[1] - centre->y) > kFootprintHalfNorthM ||
            !valid(i, j))
          continue;
        for (size_t c = 0; c < 3; ++c) out.rgb[c] += std::clamp(bands_[c].at(i, j) * 2e-5 - 0.1 - haze_[c], 0.0, 1.0);
        ++out.pixels;
      }
    for (double& v : out.rgb) v /= std::max(1, out.pixels);
    return out;
  }

 private:
  bool valid(int i, int j) const {
    for (const auto& b : bands_)
      if (b.isNodata(b.at(i, j))) return false;
    return true;
  }
  std::array<Raster, 3> bands_;
  std::array<double, 3> haze_{};
  bool ok_ = true;
};

// Metres east and north of `p` (equirectangular: the footprint is a few hundred metres).
inline glm::dvec2 offsetM(const Place& p, glm::dvec2 lonLat) {
  constexpr double kM = 3.14159265358979323846 / 180.0 * 6371000.0;
  return {(lonLat.x - p.lonDeg) * kM * std::cos(p.latDeg * 3.14159265358979323846 / 180.0), (lonLat.y - p.latDeg) * kM};
}

// The acquisition sun's shading relative to flat ground, k · max(0, n · s) + (1 − k) over
// k · s_up + (1 − k), for a tile pixel: n from the height tile by central differences
// (one-sided at its edges). Multiplying an albedo tile by it gives the ground as photographed.
struct Relight {
  glm::dvec3 sun{0.0, 0.0, 1.0};  // unit, east-north-up
  double k = 0.8;
  double at(const HeightTile& h, int i, int j, double pixelM) const {
    const auto height = [&](int x, int y) {
      return static_cast<double>(h.at(std::clamp(x, 0, h.size - 1), std::clamp(y, 0, h.size - 1)));
    };
    const int il = std::max(i - 1, 0), ir = std::min(i + 1, h.size - 1), jn = std::max(j - 1, 0),
              js = std::min(j + 1, h.size - 1);
    const double dx = (height(ir, j) - height(il, j)) / ((ir - il) * pixelM);
    const double dy = (height(i, jn) - height(i, js)) / ((js - jn) * pixelM);  // rows run south
    const glm::dvec3 n = glm::normalize(glm::dvec3(-dx, -dy, 1.0));
    if (!std::isfinite(n.z)) return 1.0;
    return (k * std::max(0.0, glm::dot(n, sun)) + 1.0 - k) / (k * sun.z + 1.0 - k);
  }
};

// Mean over the max-zoom imagery pixels whose centres lie in the footprint around `p`; with
// `relight`, each pixel's linear colour multiplied by its shading first.
inline LinearRgb tileFootprintMean(const std::filesystem::path& dataset, const DatasetMeta& meta, const Place& p,
                                   const std::optional<Relight>& relight = std::nullopt) {
  LinearRgb out;
  const double dLat = 2.0 * kFootprintHalfNorthM / 111000.0, dLon = 2.0 * dLat;
  const geo::GeoBounds box{p.lonDeg - dLon, p.latDeg - dLat, p.lonDeg + dLon, p.latDeg + dLat};
  for (const auto& id : geo::tilesCovering(box, meta.maxZoom)) {
    auto tile = readColorTile(imageryTilePath(dataset, id, *meta.imagery), id, kTileSize);
    auto heights = readHeightTile(elevationTilePath(dataset, id), id, meta.elevationEncoding, kTileSize);
    if (!tile || (relight && !heights)) continue;
    const double pixelM = geo::groundResolution(p.latDeg, id.z, tile->size);
    for (int j = 0; j < tile->size; ++j)
      for (int i = 0; i < tile->size; ++i) {
        const glm::dvec2 o = offsetM(p, geo::pixelToLonLat(id, {i + 0.5, j + 0.5}, tile->size));
        if (std::abs(o.x) > kFootprintHalfEastM || std::abs(o.y) > kFootprintHalfNorthM) continue;
        const uint8_t* px =
            &tile->rgba[(static_cast<size_t>(j) * static_cast<size_t>(tile->size) + static_cast<size_t>(i)) * 4];
        if (px[3] == 0) continue;
        const double shade = relight ? relight->at(*heights, i, j, pixelM) : 1.0;
        for (size_t c = 0; c < 3; ++c) out.rgb[c] += shade * vegstream::testing::srgbToLinear(px[c] / 255.0);
        ++out.pixels;
      }
  }
  for (double& v : out.rgb) v /= std::max(1, out.pixels);
  return out;
}

}  // namespace vegstream::datasets::test
