#include "streaming/dataset_snapshot.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "datasets/landcover.h"
#include "datasets/tile_codec.h"
#include "geo/projection.h"
#include "geo/xyz_tiles.h"
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

// Calls visit(tile, colInTile, rowInTile, mosaicIndex) for every mosaic pixel, tile by tile, so
// each tile is decoded once.
template <typename LoadTile, typename Visit>
Status forEachTilePixel(const MercatorRaster& g, LoadTile&& load, Visit&& visit) {
  const double half = geo::kWebMercatorHalfWorldM;
  const auto gcol0 = static_cast<int64_t>(std::llround((g.x0 + half) / g.pixelM - 0.5));
  const auto grow0 = static_cast<int64_t>(std::llround((half - g.y0) / g.pixelM - 0.5));
  const int n = datasets::kTileSize;
  for (int64_t ty = grow0 / n; ty <= (grow0 + g.height - 1) / n; ++ty) {
    for (int64_t tx = gcol0 / n; tx <= (gcol0 + g.width - 1) / n; ++tx) {
      const geo::TileId id{g.zoom, static_cast<int>(tx), static_cast<int>(ty)};
      auto loaded = load(id);
      if (!loaded) return loaded.error();
      if (!*loaded) continue;  // no tile: no data there
      for (int py = 0; py < n; ++py) {
        const int64_t row = ty * n + py - grow0;
        if (row < 0 || row >= g.height) continue;
        for (int px = 0; px < n; ++px) {
          const int64_t col = tx * n + px - gcol0;
          if (col < 0 || col >= g.width) continue;
          visit(**loaded, px, py, static_cast<size_t>(row) * static_cast<size_t>(g.width) + static_cast<size_t>(col));
        }
      }
    }
  }
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
  auto loadHeight = [&](const geo::TileId& id) -> Result<std::optional<datasets::HeightTile>> {
    const std::string path = datasetRelativePath({TileLayer::Height, id}, meta);
    auto bytes = source.readText(path);
    if (!bytes) {
      if (bytes.error().kind == ErrorKind::NotFound) return std::optional<datasets::HeightTile>{};
      return bytes.error();
    }
    const auto* data = reinterpret_cast<const uint8_t*>(bytes->data());
    auto t = datasets::decodeHeightTile({data, bytes->size()}, id, meta.elevationEncoding, datasets::kTileSize,
                                        source.describe() + "/" + path);
    if (!t) return t.error();
    return std::optional<datasets::HeightTile>(std::move(*t));
  };
  Status s = forEachTilePixel(mosaic, loadHeight, [&](const datasets::HeightTile& t, int px, int py, size_t i) {
    mosaic.heights[i] = t.at(px, py);
  });
  if (!s) return s.error();
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
                                        const MercatorRaster& grid) {
  if (!meta.imagery)
    return makeError(ErrorKind::InvalidInput, source.describe() + ": the dataset has no imagery");
  ImageryMosaic mosaic;
  static_cast<MercatorRaster&>(mosaic) = grid;
  mosaic.rgba.assign(pixels(grid) * 4, 0);
  if (meta.ndvi) mosaic.ndvi.assign(pixels(grid), 0);
  if (meta.landcover) mosaic.landcover.assign(pixels(grid), 0);
  // Both layers of one tile at once: the NDVI tile lies over the imagery tile pixel for pixel.
  auto loadImagery = [&](const geo::TileId& id) -> Result<std::optional<datasets::ColorTile>> {
    const std::string path = datasetRelativePath({TileLayer::Imagery, id}, meta);
    auto bytes = source.readText(path);
    if (!bytes) {
      if (bytes.error().kind == ErrorKind::NotFound) return std::optional<datasets::ColorTile>{};
      return bytes.error();
    }
    auto t = datasets::decodeColorTile({reinterpret_cast<const uint8_t*>(bytes->data()), bytes->size()}, id,
                                       datasets::kTileSize, source.describe() + "/" + path);
    if (!t) return t.error();
    if (meta.ndvi) {
      const std::string ndviPath = datasets::ndviTilePath({}, id).generic_string();
      auto ndviBytes = source.readText(ndviPath);
      if (ndviBytes) {
        auto n = datasets::decodeNdviTile({reinterpret_cast<const uint8_t*>(ndviBytes->data()), ndviBytes->size()},
                                          id, source.describe() + "/" + ndviPath, t->size);
        if (!n) return n.error();
        t->ndvi = std::move(*n);
      } else if (ndviBytes.error().kind != ErrorKind::NotFound) {
        return ndviBytes.error();
      }
    }
    return std::optional<datasets::ColorTile>(std::move(*t));
  };
  Status s = forEachTilePixel(mosaic, loadImagery, [&](const datasets::ColorTile& t, int px, int py, size_t i) {
    const size_t at = (static_cast<size_t>(py) * static_cast<size_t>(t.size) + static_cast<size_t>(px));
    for (size_t c = 0; c < 4; ++c) mosaic.rgba[4 * i + c] = t.rgba[4 * at + c];
    if (!t.ndvi.empty()) mosaic.ndvi[i] = t.ndvi[at];
  });
  if (!s) return s.error();
  if (!meta.landcover) return mosaic;
  // The landcover tiles of the same ids over the same pixels (a missing one: 0, no class).
  auto loadClasses = [&](const geo::TileId& id) -> Result<std::optional<datasets::LandcoverTile>> {
    auto classes = loadLandcoverClasses(source, id, datasets::kTileSize);
    if (!classes) return classes.error();
    if (classes->empty()) return std::optional<datasets::LandcoverTile>{};
    datasets::LandcoverTile t;
    t.id = id;
    t.classes = std::move(*classes);
    return std::optional<datasets::LandcoverTile>(std::move(t));
  };
  s = forEachTilePixel(mosaic, loadClasses, [&](const datasets::LandcoverTile& t, int px, int py, size_t i) {
    mosaic.landcover[i] = t.at(px, py);
  });
  if (!s) return s.error();
  return mosaic;
}

}  // namespace vegstream::streaming
