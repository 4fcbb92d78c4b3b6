// Point queries on a dataset directory: bilinear between pixel centres, across tile borders,
// over an LRU of decoded tiles (see dataset_reader.h).

#include "datasets/dataset_reader.h"

#include <algorithm>
#include <cmath>
#include <system_error>

#include <spdlog/fmt/fmt.h>

namespace vegstream::datasets {
namespace fs = std::filesystem;

namespace {

int floorDiv(int64_t a, int b) { return static_cast<int>(a >= 0 ? a / b : -((-a + b - 1) / b)); }

// The four pixels around a point at zoom z and their bilinear weights, in global pixel
// coordinates (tile x · size + pixel i).
struct Footprint {
  int64_t x0 = 0, y0 = 0;
  double fx = 0.0, fy = 0.0;
};

Footprint footprint(double latDeg, double lonDeg, int z, int tileSize) {
  const glm::dvec2 t = geo::lonLatToTileXY({lonDeg, latDeg}, z);
  const double gx = t.x * tileSize - 0.5, gy = t.y * tileSize - 0.5;
  Footprint f;
  const double x0 = std::floor(gx), y0 = std::floor(gy);
  f.x0 = static_cast<int64_t>(x0);
  f.y0 = static_cast<int64_t>(y0);
  f.fx = gx - x0;
  f.fy = gy - y0;
  return f;
}

struct PixelRef {
  geo::TileId tile;
  int i = 0, j = 0;
  bool valid = false;
};

PixelRef pixelRef(int64_t gx, int64_t gy, int z, int tileSize) {
  PixelRef p;
  const int tx = floorDiv(gx, tileSize), ty = floorDiv(gy, tileSize);
  const int64_t side = int64_t{1} << z;
  if (tx < 0 || ty < 0 || tx >= side || ty >= side) return p;
  p.tile = {z, tx, ty};
  p.i = static_cast<int>(gx - int64_t{tx} * tileSize);
  p.j = static_cast<int>(gy - int64_t{ty} * tileSize);
  p.valid = true;
  return p;
}

// Bilinear between pixel centres at zoom z: for each of the four pixels around f with a
// weight > 0 whose tile (getTile: Result<shared_ptr<const Tile>>) exists, add(tile, p, w)
// adds the pixel weighted by w to the caller's sum and returns whether it held data. Returns
// the weight of those that did (the sum's divisor; 0: none did), or getTile's error.
template <class GetTile, class Add>
Result<double> bilinearWeight(const Footprint& f, int z, int size, GetTile&& getTile, Add&& add) {
  double weight = 0.0;
  for (int k = 0; k < 4; ++k) {
    const int dx = k & 1, dy = k >> 1;
    const double w = (dx ? f.fx : 1.0 - f.fx) * (dy ? f.fy : 1.0 - f.fy);
    const PixelRef p = pixelRef(f.x0 + dx, f.y0 + dy, z, size);
    if (!p.valid || w <= 0.0) continue;
    auto tile = getTile(p.tile);
    if (!tile) return tile.error();
    if (!*tile) continue;
    if (add(**tile, p, w)) weight += w;
  }
  return weight;
}

size_t pixelIndex(const PixelRef& p, int size) {
  return static_cast<size_t>(p.j) * static_cast<size_t>(size) + static_cast<size_t>(p.i);
}

}  // namespace

Result<DatasetReader> DatasetReader::open(const fs::path& datasetDir, size_t cachedTiles) {
  assert(cachedTiles >= 4);
  std::error_code ec;
  if (!fs::is_directory(datasetDir, ec))
    return makeError(ErrorKind::NotFound, fmt::format("{}: no such dataset directory", datasetDir.string()));
  auto meta = readDatasetMeta(datasetDir);
  if (!meta) return meta.error();
  return DatasetReader(datasetDir, std::move(*meta), cachedTiles);
}

bool DatasetReader::contains(double latDeg, double lonDeg) const {
  const geo::GeoBounds& b = meta_.bounds;
  if (!(latDeg >= b.southDeg && latDeg <= b.northDeg)) return false;
  if (b.crossesAntimeridian()) return lonDeg >= b.westDeg || lonDeg <= b.eastDeg;
  return lonDeg >= b.westDeg && lonDeg <= b.eastDeg;
}

const DatasetReader::Entry* DatasetReader::cached(const Key& key) {
  auto it = index_.find(key);
  if (it == index_.end()) return nullptr;
  lru_.splice(lru_.begin(), lru_, it->second);
  return &lru_.front();
}

void DatasetReader::insert(Entry entry) {
  const Key key = entry.key;
  lru_.push_front(std::move(entry));
  index_[key] = lru_.begin();
  while (lru_.size() > capacity_) {
    index_.erase(lru_.back().key);
    lru_.pop_back();
  }
}

template <class Tile, class PathOf, class Read>
Result<std::shared_ptr<const Tile>> DatasetReader::cachedTile(const Key& key, std::shared_ptr<const Tile> Entry::*slot,
                                                              bool present, PathOf&& pathOf, Read&& read) {
  if (const Entry* e = cached(key)) return e->*slot;
  Entry entry{key, nullptr, nullptr, nullptr};
  const fs::path path = pathOf();
  std::error_code ec;
  if (present && fs::exists(path, ec)) {
    Result<Tile> tile = read(path);  // checks the size
    if (!tile) return tile.error();
    entry.*slot = std::make_shared<const Tile>(std::move(*tile));
    ++decoded_;
  }
  insert(entry);
  return entry.*slot;
}

Result<std::shared_ptr<const HeightTile>> DatasetReader::heightTile(const geo::TileId& id) {
  return cachedTile(
      Key{id, Layer::Height}, &Entry::height, true, [&] { return elevationTilePath(dir_, id); },
      [&](const fs::path& path) { return readHeightTile(path, id, meta_.elevationEncoding, meta_.tileSize); });
}

Result<std::shared_ptr<const ColorTile>> DatasetReader::colorTile(const geo::TileId& id) {
  const Key key{id, Layer::Color};
  if (const Entry* e = cached(key)) return e->color;
  Entry entry{key, nullptr, nullptr, nullptr};
  std::optional<ColorTile> tile;
  std::error_code ec;
  if (meta_.imagery) {
    const fs::path path = imageryTilePath(dir_, id, *meta_.imagery);
    if (fs::exists(path, ec)) {
      auto t = readColorTile(path, id, meta_.tileSize);  // checks the size
      if (!t) return t.error();
      tile = std::move(*t);
    }
  }
  if (meta_.ndvi) {
    const fs::path path = ndviTilePath(dir_, id);
    if (fs::exists(path, ec)) {
      auto n = readNdviTile(path, id, meta_.tileSize);  // checks the size
      if (!n) return n.error();
      if (!tile) {
        tile.emplace();
        tile->id = id;
        tile->size = meta_.tileSize;
        tile->rgba.assign(static_cast<size_t>(meta_.tileSize) * static_cast<size_t>(meta_.tileSize) * 4, 0);
      }
      tile->ndvi = std::move(*n);
    }
  }
  if (tile) {
    entry.color = std::make_shared<const ColorTile>(std::move(*tile));
    ++decoded_;
  }
  insert(entry);
  return entry.color;
}

Result<std::shared_ptr<const LandcoverTile>> DatasetReader::landcoverTile(const geo::TileId& id) {
  return cachedTile(
      Key{id, Layer::Landcover}, &Entry::landcover, meta_.landcover.has_value(),
      [&] { return landcoverTilePath(dir_, id); },
      [&](const fs::path& path) { return readLandcoverTile(path, id, meta_.tileSize); });
}

Result<std::shared_ptr<const CanopyTile>> DatasetReader::canopyTile(const geo::TileId& id) {
  return cachedTile(
      Key{id, Layer::Canopy}, &Entry::canopy, meta_.canopyZoom.has_value(), [&] { return canopyTilePath(dir_, id); },
      [&](const fs::path& path) { return readCanopyTile(path, id, meta_.tileSize); });
}

Result<double> DatasetReader::heightAtZoom(double latDeg, double lonDeg, int z) {
  const int size = meta_.tileSize;
  const Footprint f = footprint(latDeg, lonDeg, z, size);
  double sum = 0.0;
  auto weight = bilinearWeight(
      f, z, size, [&](const geo::TileId& id) { return heightTile(id); },
      [&](const HeightTile& tile, const PixelRef& p, double w) {
        const float h = tile.at(p.i, p.j);
        if (std::isnan(h)) return false;
        sum += w * h;
        return true;
      });
  if (!weight) return weight.error();
  return *weight > 0.0 ? sum / *weight : std::nan("");
}

Result<double> DatasetReader::heightAt(double latDeg, double lonDeg) {
  if (!contains(latDeg, lonDeg)) {
    const geo::GeoBounds& b = meta_.bounds;
    return makeError(ErrorKind::InvalidInput,
                     fmt::format("lat {:.6f}, lon {:.6f} is outside the dataset {} (lat {:.6f} … {:.6f}, "
                                 "lon {:.6f} … {:.6f})",
                                 latDeg, lonDeg, dir_.string(), b.southDeg, b.northDeg, b.westDeg, b.eastDeg));
  }
  for (int z = meta_.maxZoom; z >= meta_.minZoom; --z) {
    auto h = heightAtZoom(latDeg, lonDeg, z);
    if (!h || !std::isnan(*h)) return h;
  }
  return std::nan("");
}

Result<std::optional<Rgb8>> DatasetReader::colorAt(double latDeg, double lonDeg) {
  if (!meta_.imagery || !contains(latDeg, lonDeg)) return std::optional<Rgb8>{};
  const int size = meta_.tileSize;
  for (int z = meta_.maxZoom; z >= meta_.minZoom; --z) {
    const Footprint f = footprint(latDeg, lonDeg, z, size);
    double sum[3] = {0.0, 0.0, 0.0};
    auto weight = bilinearWeight(
        f, z, size, [&](const geo::TileId& id) { return colorTile(id); },
        [&](const ColorTile& tile, const PixelRef& p, double w) {
          const size_t o = pixelIndex(p, size) * 4;
          const auto& px = tile.rgba;
          if (px[o + 3] == 0) return false;
          for (int c = 0; c < 3; ++c) sum[c] += w * px[o + static_cast<size_t>(c)];
          return true;
        });
    if (!weight) return weight.error();
    if (*weight > 0.0) {
      Rgb8 rgb;
      for (int c = 0; c < 3; ++c)
        rgb[static_cast<size_t>(c)] = static_cast<uint8_t>(std::lround(std::clamp(sum[c] / *weight, 0.0, 255.0)));
      return std::optional<Rgb8>(rgb);
    }
  }
  return std::optional<Rgb8>{};
}

Result<std::optional<float>> DatasetReader::ndviAt(double latDeg, double lonDeg) {
  if (!meta_.ndvi || !contains(latDeg, lonDeg)) return std::optional<float>{};
  const int size = meta_.tileSize;
  for (int z = meta_.maxZoom; z >= meta_.minZoom; --z) {
    const Footprint f = footprint(latDeg, lonDeg, z, size);
    double sum = 0.0;
    auto weight = bilinearWeight(
        f, z, size, [&](const geo::TileId& id) { return colorTile(id); },
        [&](const ColorTile& tile, const PixelRef& p, double w) {
          if (tile.ndvi.empty()) return false;
          const float v = ndviFromByte(tile.ndvi[pixelIndex(p, size)]);
          if (std::isnan(v)) return false;
          sum += w * v;
          return true;
        });
    if (!weight) return weight.error();
    if (*weight > 0.0) return std::optional<float>(static_cast<float>(sum / *weight));
  }
  return std::optional<float>{};
}

// Nearest pixel, not bilinear: classes are categories. The pixel whose square holds the point
// (its global pixel coordinates floored), at the finest zoom where it has a class.
Result<std::optional<uint8_t>> DatasetReader::landcoverAt(double latDeg, double lonDeg) {
  if (!meta_.landcover || !contains(latDeg, lonDeg)) return std::optional<uint8_t>{};
  const int size = meta_.tileSize;
  for (int z = meta_.maxZoom; z >= meta_.minZoom; --z) {
    const glm::dvec2 t = geo::lonLatToTileXY({lonDeg, latDeg}, z);
    const PixelRef p =
        pixelRef(static_cast<int64_t>(std::floor(t.x * size)), static_cast<int64_t>(std::floor(t.y * size)), z, size);
    if (!p.valid) continue;
    auto tile = landcoverTile(p.tile);
    if (!tile) return tile.error();
    if (!*tile) continue;
    const uint8_t code = (*tile)->at(p.i, p.j);
    if (code != 0) return std::optional<uint8_t>(code);
  }
  return std::optional<uint8_t>{};
}

// The pixel whose square holds the point, at the layer's own zoom.
Result<std::optional<float>> DatasetReader::canopyAt(double latDeg, double lonDeg) {
  if (!meta_.canopyZoom || !contains(latDeg, lonDeg)) return std::optional<float>{};
  const int size = meta_.tileSize, z = *meta_.canopyZoom;
  const glm::dvec2 t = geo::lonLatToTileXY({lonDeg, latDeg}, z);
  const PixelRef p =
      pixelRef(static_cast<int64_t>(std::floor(t.x * size)), static_cast<int64_t>(std::floor(t.y * size)), z, size);
  if (!p.valid) return std::optional<float>{};
  auto tile = canopyTile(p.tile);
  if (!tile) return tile.error();
  if (!*tile) return std::optional<float>{};
  const float h = canopyHeightOf((*tile)->at(p.i, p.j));
  return std::isnan(h) ? std::optional<float>{} : std::optional<float>(h);
}

}  // namespace vegstream::datasets
