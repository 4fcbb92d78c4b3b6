// The tile check of a dataset (tile_check.h): each layer's own decoder, then its size.

#include "streaming/tile_check.h"

#include <cstdio>

#include "datasets/canopy.h"
#include "datasets/landcover.h"
#include "datasets/tile_codec.h"

namespace vegstream::streaming {
namespace {

enum class Layer { None, Elevation, Imagery, Ndvi, Landcover, Canopy };

// "imagery/12/758/1608.jpg" → (Imagery, 12/758/1608); Layer::None when it is no tile path.
Layer parseTilePath(const std::string& path, geo::TileId& id) {
  const size_t slash = path.find('/');
  if (slash == std::string::npos) return Layer::None;
  const std::string head = path.substr(0, slash);
  const Layer layer = head == "elevation" ? Layer::Elevation
                      : head == "imagery" ? Layer::Imagery
                      : head == "ndvi"    ? Layer::Ndvi
                      : head == "landcover" ? Layer::Landcover
                      : head == "canopy"    ? Layer::Canopy
                                            : Layer::None;
  int z = 0, x = 0, y = 0, used = 0;
  if (layer == Layer::None ||
      std::sscanf(path.c_str() + slash + 1, "%d/%d/%d.%*[a-z]%n", &z, &x, &y, &used) != 3 || used == 0)
    return Layer::None;
  id = geo::TileId{z, x, y};
  return layer;
}

Status sizeIs(int size, int expected, const std::string& name) {
  if (size == expected) return {};
  return makeError(ErrorKind::InvalidInput, name + ": a tile of " + std::to_string(size) + " pixels a side where the "
                                                "dataset says " + std::to_string(expected));
}

}  // namespace

TileCheck tileCheckFor(const datasets::DatasetMeta& meta, const std::string& sourceName) {
  const datasets::ElevationEncoding encoding = meta.elevationEncoding;
  const int size = meta.tileSize;
  return [encoding, size, sourceName](const std::string& path, std::span<const uint8_t> bytes) -> Status {
    geo::TileId id;
    const Layer layer = parseTilePath(path, id);
    const std::string name = sourceName + "/" + path;
    switch (layer) {
      case Layer::None: return {};
      case Layer::Elevation: {
        auto t = datasets::decodeHeightTile(bytes, id, encoding, size, name);
        if (!t) return t.error();
        return sizeIs(t->size, size, name);
      }
      case Layer::Imagery: {
        auto t = datasets::decodeColorTile(bytes, id, size, name);
        if (!t) return t.error();
        return sizeIs(t->size, size, name);
      }
      case Layer::Ndvi: {
        auto t = datasets::decodeNdviTile(bytes, id, name, size);
        if (!t) return t.error();
        return {};
      }
      case Layer::Landcover: {
        auto t = datasets::decodeLandcoverTile(bytes, id, name, size);
        if (!t) return t.error();
        return {};
      }
      case Layer::Canopy: {
        auto t = datasets::decodeCanopyTile(bytes, id, name, size);
        if (!t) return t.error();
        return {};
      }
    }
    return {};
  };
}

}  // namespace vegstream::streaming
