#pragma once
// Reading a dataset directory (dataset_format.h) point by point: `vegstream query`, `info`,
// tests, and later the vegetation tools that need the height and base colour under a plant.
//
// Heights and colours are bilinear between pixel centres (pixel (i, j) of a tile sampled at
// its centre), across tile borders, at the finest zoom that has data at the point; pixels
// without data (missing tile, alpha 0) drop out of the four and the remaining weights are
// renormalised, so values near the edge of the data stay defined. Decoded tiles are kept in a
// small LRU. A reader is not thread-safe: give each thread its own.

#include <array>
#include <cstdint>
#include <filesystem>
#include <list>
#include <memory>
#include <optional>
#include <unordered_map>

#include "core/result.h"
#include "datasets/dataset_format.h"
#include "datasets/canopy.h"
#include "datasets/landcover.h"
#include "datasets/tile_codec.h"

namespace vegstream::datasets {

using Rgb8 = std::array<uint8_t, 3>;

class DatasetReader {
 public:
  // Reads and checks dataset.json. NotFound: no such directory / no dataset.json; InvalidInput:
  // a bad field (the message names the file and the field).
  static Result<DatasetReader> open(const std::filesystem::path& datasetDir, size_t cachedTiles = 64);

  const DatasetMeta& meta() const { return meta_; }
  const std::filesystem::path& dir() const { return dir_; }

  // True when the point lies inside meta().bounds (edges included).
  bool contains(double latDeg, double lonDeg) const;

  // Height in metres. Outside the bounds: InvalidInput naming the point and the bounds. Inside
  // but with no data at any zoom: NaN. A tile that cannot be decoded: the codec's error (names
  // the file).
  Result<double> heightAt(double latDeg, double lonDeg);
  // Same at one zoom only (NaN where that zoom has no data there).
  Result<double> heightAtZoom(double latDeg, double lonDeg, int z);

  // Base colour (sRGB, rounded). nullopt: no imagery at the point (or the dataset has none).
  Result<std::optional<Rgb8>> colorAt(double latDeg, double lonDeg);
  // NDVI (−1 … 1, to the encoding's step of 1/127), bilinear like colorAt over the NDVI layer.
  // nullopt: no NDVI at the point, outside the bounds, or a dataset without the layer.
  Result<std::optional<float>> ndviAt(double latDeg, double lonDeg);
  // Landcover class code (landcover.h; never blended): the pixel whose square holds the point,
  // at the finest zoom where that pixel has a class. nullopt: no class there at any zoom,
  // outside the bounds, or a dataset without the layer. Codes the scheme does not know are
  // returned as stored.
  Result<std::optional<uint8_t>> landcoverAt(double latDeg, double lonDeg);
  // Canopy height above the ground (m, to the encoding's 0.1 m): the pixel whose square holds the
  // point at the canopy layer's own zoom (canopy.h). nullopt: no height there, outside the bounds,
  // or a dataset without the layer.
  Result<std::optional<float>> canopyAt(double latDeg, double lonDeg);

  // One decoded tile; nullptr when the dataset has no such tile. A colour tile carries the NDVI
  // layer's tile in `ndvi` when the dataset has the layer (empty where that tile is missing);
  // where only the NDVI tile exists its rgba is all "no data".
  Result<std::shared_ptr<const HeightTile>> heightTile(const geo::TileId& id);
  Result<std::shared_ptr<const ColorTile>> colorTile(const geo::TileId& id);
  // The landcover layer's tile; nullptr when there is none (or no layer).
  Result<std::shared_ptr<const LandcoverTile>> landcoverTile(const geo::TileId& id);
  // The canopy layer's tile; nullptr when there is none (or no layer).
  Result<std::shared_ptr<const CanopyTile>> canopyTile(const geo::TileId& id);

  // Tiles decoded from disk so far (the LRU's misses), for tests.
  uint64_t tilesDecoded() const { return decoded_; }

 private:
  DatasetReader(std::filesystem::path dir, DatasetMeta meta, size_t cachedTiles)
      : dir_(std::move(dir)), meta_(std::move(meta)), capacity_(cachedTiles) {}

  enum class Layer : uint8_t { Height, Color, Landcover, Canopy };
  struct Key {
    geo::TileId id;
    Layer layer = Layer::Height;
    bool operator==(const Key&) const = default;
  };
  struct KeyHash {
    size_t operator()(const Key& k) const {
      return std::hash<geo::TileId>{}(k.id) ^ (static_cast<size_t>(k.layer) * 0x5bd1e995u);
    }
  };
  struct Entry {
    Key key;
    std::shared_ptr<const HeightTile> height;
    std::shared_ptr<const ColorTile> color;
    std::shared_ptr<const LandcoverTile> landcover;
    std::shared_ptr<const CanopyTile> canopy = nullptr;
  };
  const Entry* cached(const Key& key);
  void insert(Entry entry);
  // The tile of `key` from the cache (its `slot`), else read and cached: read(path) where the
  // layer is `present` and the file pathOf() exists, else none (cached as none too).
  template <class Tile, class PathOf, class Read>
  Result<std::shared_ptr<const Tile>> cachedTile(const Key& key, std::shared_ptr<const Tile> Entry::*slot, bool present,
                                                 PathOf&& pathOf, Read&& read);

  std::filesystem::path dir_;
  DatasetMeta meta_;
  size_t capacity_;
  std::list<Entry> lru_;  // most recently used first
  std::unordered_map<Key, std::list<Entry>::iterator, KeyHash> index_;
  uint64_t decoded_ = 0;
};

}  // namespace vegstream::datasets
