// `vegstream generate` (synthetic_generator.h): samples SyntheticTerrain at the pixel centres of
// the finest zoom's tiles, writes elevation and imagery tiles through the tile codec, and lets
// the pyramid builder make the lower zooms. Pixels outside the square are nodata (alpha 0).

#include "datasets/synthetic_generator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>

#include "core/atomic_file.h"
#include "datasets/dataset_finish.h"
#include "datasets/message.h"
#include "core/parallel_for.h"
#include "datasets/tile_codec.h"
#include "geo/crs.h"

namespace vegstream::datasets {
namespace fs = std::filesystem;

namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr double kA = 6378137.0, kE2 = 6.69437999014e-3;  // WGS 84

// Metres per degree of latitude / longitude at a latitude (meridian and prime-vertical radii):
// a local equirectangular frame, exact enough for a noise domain of a few hundred km.
struct MetresPerDegree {
  double lat = 0.0, lon = 0.0;
};
MetresPerDegree metresPerDegree(double latDeg) {
  const double s = std::sin(latDeg * kDeg), w = std::sqrt(1.0 - kE2 * s * s);
  return {kA * (1.0 - kE2) / (w * w * w) * kDeg, kA / w * std::cos(latDeg * kDeg) * kDeg};
}

Status validate(const SyntheticOptions& o) {
  auto bad = [](const std::string& what) { return makeError(ErrorKind::InvalidInput, what); };
  if (!(o.centreLatDeg >= -80.0 && o.centreLatDeg <= 80.0))
    return bad(concat("--lat ", o.centreLatDeg, ": expected -80 … 80"));
  if (!(o.centreLonDeg >= -180.0 && o.centreLonDeg <= 180.0))
    return bad(concat("--lon ", o.centreLonDeg, ": expected -180 … 180"));
  if (!(o.sizeKm >= 0.1 && o.sizeKm <= 200.0)) return bad(concat("--size-km ", o.sizeKm, ": expected 0.1 … 200"));
  if (o.maxZoom < 0 || o.maxZoom > 18) return bad(concat("--max-zoom ", o.maxZoom, ": expected 1 … 18 (0: automatic)"));
  const geo::GeoBounds b = syntheticBounds(o);
  if (b.westDeg < -180.0 || b.eastDeg > 180.0)
    return bad("the generated area would cross the antimeridian; move --lon away from ±180");
  return {};
}

// Heights of one tile plus a one-pixel border (for slopes), at the pixel centres.
struct TileSamples {
  int n = 0;                           // kTileSize + 2
  std::vector<double> east, north, h;  // east per column, north per row, h row-major
  double at(int i, int j) const {
    return h[static_cast<size_t>(j + 1) * static_cast<size_t>(n) + static_cast<size_t>(i + 1)];
  }
};

TileSamples sampleTile(const SyntheticTerrain& terrain, const geo::TileId& id, const SyntheticOptions& o,
                       const MetresPerDegree& mpd) {
  TileSamples s;
  s.n = kTileSize + 2;
  const auto n = static_cast<size_t>(s.n);
  s.east.resize(n);
  s.north.resize(n);
  s.h.resize(n * n);
  for (int k = 0; k < s.n; ++k) {
    const glm::dvec2 ll = geo::pixelToLonLat(id, {k - 0.5, k - 0.5}, kTileSize);  // centre of pixel k − 1
    s.east[static_cast<size_t>(k)] = (ll.x - o.centreLonDeg) * mpd.lon;
    s.north[static_cast<size_t>(k)] = (ll.y - o.centreLatDeg) * mpd.lat;
  }
  for (size_t j = 0; j < n; ++j)
    for (size_t i = 0; i < n; ++i) s.h[j * n + i] = terrain.heightM(s.east[i], s.north[j]);
  return s;
}

// One tile's heights (NaN outside the square) and biome colours, and its height range (empty:
// lo > hi, when the tile only touches the square's edge).
struct SyntheticTile {
  HeightTile heights;
  ColorTile colours;
  double lo = std::numeric_limits<double>::infinity(), hi = -std::numeric_limits<double>::infinity();
};

SyntheticTile renderTile(const SyntheticTerrain& terrain, const geo::TileId& id, const SyntheticOptions& o,
                         const MetresPerDegree& mpd, const geo::GeoBounds& bounds) {
  const TileSamples samples = sampleTile(terrain, id, o, mpd);
  SyntheticTile t{HeightTile{id, kTileSize, std::vector<float>(static_cast<size_t>(kTileSize * kTileSize))},
                  ColorTile{id, kTileSize, std::vector<uint8_t>(static_cast<size_t>(kTileSize * kTileSize) * 4, 0)}};
  for (int j = 0; j < kTileSize; ++j) {
    const double lat = o.centreLatDeg + samples.north[static_cast<size_t>(j + 1)] / mpd.lat;
    for (int i = 0; i < kTileSize; ++i) {
      const size_t p = static_cast<size_t>(j) * kTileSize + static_cast<size_t>(i);
      const double lon = o.centreLonDeg + samples.east[static_cast<size_t>(i + 1)] / mpd.lon;
      if (lat < bounds.southDeg || lat > bounds.northDeg || lon < bounds.westDeg || lon > bounds.eastDeg) {
        t.heights.heights[p] = std::numeric_limits<float>::quiet_NaN();
        continue;
      }
      const double h = samples.at(i, j);
      const double gx = (samples.at(i + 1, j) - samples.at(i - 1, j)) /
                        (samples.east[static_cast<size_t>(i + 2)] - samples.east[static_cast<size_t>(i)]);
      const double gy = (samples.at(i, j - 1) - samples.at(i, j + 1)) /
                        (samples.north[static_cast<size_t>(j)] - samples.north[static_cast<size_t>(j + 2)]);
      const auto c = terrain.color(samples.east[static_cast<size_t>(i + 1)], samples.north[static_cast<size_t>(j + 1)],
                                   h, std::atan(std::hypot(gx, gy)));
      t.heights.heights[p] = static_cast<float>(h);
      std::copy(c.begin(), c.end(), t.colours.rgba.begin() + static_cast<std::ptrdiff_t>(p * 4));
      t.colours.rgba[p * 4 + 3] = 255;
      t.lo = std::min(t.lo, h);
      t.hi = std::max(t.hi, h);
    }
  }
  return t;
}

// The dataset's description: name, bounds, zooms, encoding and sources.
DatasetMeta syntheticMeta(const SyntheticOptions& o, const geo::GeoBounds& bounds, int maxZoom,
                          const std::vector<geo::TileId>& ids) {
  DatasetMeta meta;
  meta.name = o.name.empty() ? defaultDatasetName(o.out) : o.name;
  meta.bounds = bounds;
  meta.maxZoom = maxZoom;
  meta.minZoom = o.minZoom ? std::clamp(*o.minZoom, 0, maxZoom) : singleTileZoom(ids);
  meta.elevationEncoding = o.encoding;
  meta.imagery = ImageryFormat::Png;
  meta.attribution = "synthetic terrain generated by vegstream";
  const std::string source =
      concat("seed ", o.seed, ", ", o.sizeKm, " km square around lat ", o.centreLatDeg, ", lon ", o.centreLonDeg);
  meta.sources.push_back({"elevation", "synthetic", geo::wgs84Crs().name(), source + ", fractal relief"});
  meta.sources.push_back(
      {"imagery", "synthetic", geo::wgs84Crs().name(), source + ", biome colours from height and slope"});
  return meta;
}

}  // namespace

geo::GeoBounds syntheticBounds(const SyntheticOptions& o) {
  const MetresPerDegree mpd = metresPerDegree(o.centreLatDeg);
  const double half = o.sizeKm * 500.0;
  return {o.centreLonDeg - half / mpd.lon, o.centreLatDeg - half / mpd.lat, o.centreLonDeg + half / mpd.lon,
          o.centreLatDeg + half / mpd.lat};
}

Result<DatasetMeta> generateSyntheticDataset(const SyntheticOptions& o, const Logger& log, ProgressSink& progress) {
  assert(!o.out.empty());
  if (auto s = validate(o); !s) return s.error();
  const geo::GeoBounds bounds = syntheticBounds(o);
  const int maxZoom =
      o.maxZoom > 0 ? o.maxZoom
                    : std::clamp(static_cast<int>(std::ceil(geo::zoomForResolution(10.0, o.centreLatDeg))), 1, 18);
  const std::vector<geo::TileId> ids = geo::tilesCovering(bounds, maxZoom);
  if (ids.size() > 100000)
    return makeError(ErrorKind::InvalidInput, concat("--size-km ", o.sizeKm, " at zoom ", maxZoom, " would need ",
                                                     ids.size(), " tiles; lower --max-zoom or --size-km"));
  const SyntheticTerrain terrain(o.seed);
  const MetresPerDegree mpd = metresPerDegree(o.centreLatDeg);

  DatasetMeta meta = syntheticMeta(o, bounds, maxZoom, ids);
  log->info("generating {} tiles at zoom {} ({:.1f} m pixels), zooms {} … {}", ids.size(), maxZoom,
            geo::groundResolution(o.centreLatDeg, maxZoom), meta.minZoom, maxZoom);

  Result<DatasetMeta> result = meta;
  Status status = writeDirectoryAtomically(o.out, [&](const fs::path& tmp) -> Status {
    std::mutex mutex;
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    progress.stage(concat("zoom ", maxZoom));
    progress.addTotal(ids.size());
    Status s = parallelFor(ids.size(), o.threads, o.tasks, [&](size_t index) -> Status {
      const geo::TileId& id = ids[index];
      const SyntheticTile t = renderTile(terrain, id, o, mpd, bounds);
      if (!(t.lo <= t.hi)) {  // the tile only touches the square's edge: nothing to write
        progress.tileDone(0);
        return {};
      }
      const fs::path hp = elevationTilePath(tmp, id), cp = imageryTilePath(tmp, id, ImageryFormat::Png);
      if (auto w = writeHeightTile(hp, t.heights, o.encoding); !w) return w;
      if (auto w = writeColorTile(cp, t.colours, ImageryFormat::Png); !w) return w;
      const uint64_t bytes = fileBytes(hp) + fileBytes(cp);
      {
        std::lock_guard lock(mutex);
        lo = std::min(lo, t.lo);
        hi = std::max(hi, t.hi);
        meta.bytes += bytes;
        ++meta.elevationTiles;
        ++meta.imageryTiles;
      }
      progress.tileDone(bytes);
      return {};
    });
    if (!s) return s;
    meta.minHeightM = lo;
    meta.maxHeightM = hi;
    result = finishDataset(tmp, meta, progress, o.threads, 90, o.tasks);
    return result ? Status{} : Status{result.error()};
  });
  if (!status) return status.error();
  return result;
}

}  // namespace vegstream::datasets
