#include "streaming/dataset_snapshot.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "datasets/landcover.h"
#include "datasets/tile_codec.h"
#include "geo/projection.h"
#include "geo/xyz_tiles.h"
#include "streaming/ground_fetch.h"
#include "streaming/tile_key.h"

namespace vegstream::streaming {

namespace {

// The mosaic grid of zoom z cropped to `bounds`: pixel centres inside the bounds.
MercatorRaster gridFor(const geo::GeoBounds& bounds, int z) {
  const double pixelM = geo::mercatorResolution(z, datasets::kTileSize);
  const glm::dvec2 nw = geo::lonLatToWebMercator({bounds.westDeg, bounds.northDeg});
  const glm::dvec2 se = geo::lonLatToWebMercator({bounds.eastDeg, bounds.southDeg});
  // Global pixel indices (from the west / north edge of the world) of the first and last
  // pixel whose centre lies inside the bounds.
  const double half = geo::kWebMercatorHalfWorldM;
  const auto col0 = static_cast<int64_t>(std::ceil((nw.x + half) / pixelM - 0.5));
  const auto col1 = static_cast<int64_t>(std::floor((se.x + half) / pixelM - 0.5));
  const auto row0 = static_cast<int64_t>(std::ceil((half - nw.y) / pixelM - 0.5));
  const auto row1 = static_cast<int64_t>(std::floor((half - se.y) / pixelM - 0.5));
  MercatorRaster g;
  g.zoom = z;
  g.width = static_cast<int>(std::max<int64_t>(0, col1 - col0 + 1));
  g.height = static_cast<int>(std::max<int64_t>(0, row1 - row0 + 1));
  g.pixelM = pixelM;
  g.x0 = -half + (static_cast<double>(col0) + 0.5) * pixelM;
  g.y0 = half - (static_cast<double>(row0) + 0.5) * pixelM;
  return g;
}

uint64_t pixels(const MercatorRaster& g) { return static_cast<uint64_t>(g.width) * static_cast<uint64_t>(g.height); }

// The finest zoom whose grid fits the limits; when not even min_zoom's does (a dataset.json
// whose min_zoom is 16 over a whole park), InvalidInput before anything is allocated.
Result<int> finestZoomWithin(TileSource& source, const datasets::DatasetMeta& meta, const SnapshotLimits& limits) {
  int z = -1;
  for (int candidate = meta.minZoom; candidate <= meta.maxZoom; ++candidate) {
    const MercatorRaster g = gridFor(meta.bounds, candidate);
    if (pixels(g) <= limits.maxHeightPixels && g.width <= limits.maxSide && g.height <= limits.maxSide) z = candidate;
  }
  if (z >= 0) return z;
  const MercatorRaster g = gridFor(meta.bounds, meta.minZoom);
  return makeError(ErrorKind::InvalidInput,
                   source.describe() + "/dataset.json: at its min_zoom " + std::to_string(meta.minZoom) +
                       " the dataset's bounds are " + std::to_string(g.width) + "x" + std::to_string(g.height) +
                       " pixels; the ground mosaic stops at " + std::to_string(limits.maxHeightPixels) +
                       " pixels and " + std::to_string(limits.maxSide) + " a side (give a smaller min_zoom)");
}

// The global pixel (from the west / north edge of the world) of the grid's first column / row.
std::pair<int64_t, int64_t> gridOrigin(const MercatorRaster& g) {
  const double half = geo::kWebMercatorHalfWorldM;
  return {static_cast<int64_t>(std::llround((g.x0 + half) / g.pixelM - 0.5)),
          static_cast<int64_t>(std::llround((half - g.y0) / g.pixelM - 0.5))};
}

// The tiles of zoom g.zoom under the grid, row by row.
std::vector<geo::TileId> tilesUnder(const MercatorRaster& g) {
  std::vector<geo::TileId> ids;
  if (g.width <= 0 || g.height <= 0) return ids;
  const auto [gcol0, grow0] = gridOrigin(g);
  const int n = datasets::kTileSize;
  for (int64_t ty = grow0 / n; ty <= (grow0 + g.height - 1) / n; ++ty)
    for (int64_t tx = gcol0 / n; tx <= (gcol0 + g.width - 1) / n; ++tx)
      ids.push_back({g.zoom, static_cast<int>(tx), static_cast<int>(ty)});
  return ids;
}

// Calls visit(colInTile, rowInTile, mosaicIndex) for every mosaic pixel of tile `id`.
template <typename Visit>
void forEachPixelOf(const MercatorRaster& g, const geo::TileId& id, Visit&& visit) {
  const auto [gcol0, grow0] = gridOrigin(g);
  const int n = datasets::kTileSize;
  for (int py = 0; py < n; ++py) {
    const int64_t row = int64_t(id.y) * n + py - grow0;
    if (row < 0 || row >= g.height) continue;
    for (int px = 0; px < n; ++px) {
      const int64_t col = int64_t(id.x) * n + px - gcol0;
      if (col < 0 || col >= g.width) continue;
      visit(px, py, static_cast<size_t>(row) * static_cast<size_t>(g.width) + static_cast<size_t>(col));
    }
  }
}

// Fetches the files of `tiles` (pathOf(id)) as one batch (ground_fetch.h) and hands each one
// that arrived to use(id, bytes, name), which decodes and pastes it. A file the source does not
// have is no data there. A file that failed (retries and deadline spent, or that does not
// decode) is no data too, with one warning for the layer: one bad answer does not end the run.
// Only when every file failed is it an error (the first failure): there is no ground at all.
template <typename PathOf, typename Use>
Status loadLayer(TileSource& source, const std::vector<geo::TileId>& tiles, const SnapshotLimits& limits,
                 PathOf&& pathOf, Use&& use) {
  std::vector<std::string> paths;
  for (const geo::TileId& id : tiles) paths.push_back(pathOf(id));
  size_t failed = 0, loaded = 0;
  std::optional<Error> first;
  BatchFetchOptions batch;
  batch.deadlineMs = limits.deadlineMs;
  fetchBatch(source, paths, batch, [&](size_t i, FetchResult&& r) {
    Status s;
    if (r.outcome == FetchOutcome::Missing) return;
    if (r.outcome == FetchOutcome::Ok)
      s = use(tiles[i], std::span<const uint8_t>(r.bytes), source.describe() + "/" + paths[i]);
    else
      s = makeError(ErrorKind::InvalidInput, r.message);  // the source the user named does not deliver
    if (s) {
      ++loaded;
      return;
    }
    ++failed;
    if (!first) first = s.error();
  });
  if (failed == 0) return {};
  if (loaded == 0) return *first;
  if (limits.log)
    limits.log->warn("ground: {} of {} tiles failed and are taken as no data (first: {})", failed, tiles.size(),
                     first->message);
  return {};
}

}  // namespace

Result<HeightMosaic> loadGroundHeights(TileSource& source, const datasets::DatasetMeta& meta,
                                       const SnapshotLimits& limits) {
  HeightMosaic mosaic;
  const auto hz = finestZoomWithin(source, meta, limits);
  if (!hz) return hz.error();
  static_cast<MercatorRaster&>(mosaic) = gridFor(meta.bounds, *hz);
  mosaic.heights.assign(pixels(mosaic), std::numeric_limits<float>::quiet_NaN());
  auto pathOf = [&](const geo::TileId& id) { return datasetRelativePath({TileLayer::Height, id}, meta); };
  auto use = [&](const geo::TileId& id, std::span<const uint8_t> bytes, const std::string& name) -> Status {
    auto t = datasets::decodeHeightTile(bytes, id, meta.elevationEncoding, datasets::kTileSize, name);
    if (!t) return t.error();
    if (t->size != datasets::kTileSize)
      return makeError(ErrorKind::InvalidInput, name + ": " + std::to_string(t->size) + " pixels a side, not " +
                                                    std::to_string(datasets::kTileSize));
    forEachPixelOf(mosaic, id, [&](int px, int py, size_t i) { mosaic.heights[i] = t->at(px, py); });
    return {};
  };
  if (Status s = loadLayer(source, tilesUnder(mosaic), limits, pathOf, use); !s) return s.error();
  return mosaic;
}

Result<std::vector<uint8_t>> loadLandcoverClasses(TileSource& source, const geo::TileId& id, int size) {
  const std::string path = datasets::landcoverTilePath({}, id).generic_string();
  auto bytes = source.readText(path);
  if (!bytes) {
    if (bytes.error().kind == ErrorKind::NotFound) return std::vector<uint8_t>{};
    return bytes.error();
  }
  auto t = datasets::decodeLandcoverTile({reinterpret_cast<const uint8_t*>(bytes->data()), bytes->size()}, id,
                                         source.describe() + "/" + path, size);
  if (!t) return t.error();
  return std::move(t->classes);
}

Result<ImageryMosaic> loadGroundImagery(TileSource& source, const datasets::DatasetMeta& meta,
                                        const MercatorRaster& grid, const SnapshotLimits& limits) {
  if (!meta.imagery)
    return makeError(ErrorKind::InvalidInput, source.describe() + ": the dataset has no imagery");
  ImageryMosaic mosaic;
  static_cast<MercatorRaster&>(mosaic) = grid;
  mosaic.rgba.assign(pixels(grid) * 4, 0);
  if (meta.ndvi) mosaic.ndvi.assign(pixels(grid), 0);
  if (meta.landcover) mosaic.landcover.assign(pixels(grid), 0);
  const int n = datasets::kTileSize;
  auto sizeProblem = [n](const std::string& name, int size) {
    return makeError(ErrorKind::InvalidInput,
                     name + ": " + std::to_string(size) + " pixels a side, not " + std::to_string(n));
  };
  std::vector<geo::TileId> withImagery;  // the NDVI tiles lie over these, pixel for pixel
  auto imageryPath = [&](const geo::TileId& id) { return datasetRelativePath({TileLayer::Imagery, id}, meta); };
  auto useImagery = [&](const geo::TileId& id, std::span<const uint8_t> bytes, const std::string& name) -> Status {
    auto t = datasets::decodeColorTile(bytes, id, datasets::kTileSize, name);
    if (!t) return t.error();
    if (t->size != n) return sizeProblem(name, t->size);
    forEachPixelOf(mosaic, id, [&](int px, int py, size_t i) {
      const size_t at = static_cast<size_t>(py) * static_cast<size_t>(n) + static_cast<size_t>(px);
      for (size_t c = 0; c < 4; ++c) mosaic.rgba[4 * i + c] = t->rgba[4 * at + c];
    });
    withImagery.push_back(id);
    return {};
  };
  if (Status s = loadLayer(source, tilesUnder(mosaic), limits, imageryPath, useImagery); !s) return s.error();
  if (meta.ndvi && !withImagery.empty()) {
    auto ndviPath = [](const geo::TileId& id) { return datasets::ndviTilePath({}, id).generic_string(); };
    auto useNdvi = [&](const geo::TileId& id, std::span<const uint8_t> bytes, const std::string& name) -> Status {
      auto v = datasets::decodeNdviTile(bytes, id, name, n);
      if (!v) return v.error();
      forEachPixelOf(mosaic, id, [&](int px, int py, size_t i) { mosaic.ndvi[i] = (*v)[size_t(py) * size_t(n) + size_t(px)]; });
      return {};
    };
    if (Status s = loadLayer(source, withImagery, limits, ndviPath, useNdvi); !s) return s.error();
  }
  if (!meta.landcover) return mosaic;
  // The landcover tiles of the same ids over the same pixels (a missing one: 0, no class).
  auto landcoverPath = [](const geo::TileId& id) { return datasets::landcoverTilePath({}, id).generic_string(); };
  auto useLandcover = [&](const geo::TileId& id, std::span<const uint8_t> bytes, const std::string& name) -> Status {
    auto t = datasets::decodeLandcoverTile(bytes, id, name, n);
    if (!t) return t.error();
    forEachPixelOf(mosaic, id, [&](int px, int py, size_t i) { mosaic.landcover[i] = t->at(px, py); });
    return {};
  };
  if (Status s = loadLayer(source, tilesUnder(mosaic), limits, landcoverPath, useLandcover); !s) return s.error();
  return mosaic;
}

}  // namespace vegstream::streaming
