// Source tiles decoded and, when 512 pixels wide, split into four 256-pixel tiles
// (xyz_source_tiles.h).

#include "datasets/xyz_source_tiles.h"

#include <algorithm>
#include <cassert>

#include "datasets/message.h"

namespace vegstream::datasets {
namespace {

Status checkSize(const XyzSource& source, const geo::TileId& id, int size) {
  if (size == kTileSize || size == kLargeSourceTileSize) return {};
  return makeError(ErrorKind::Unsupported, concat("tile '", source.tileName(id), "' is ", size,
                                                  " pixels wide; vegstream imports 256- and 512-pixel tiles"));
}

// Copies the 256² block (i, j) of a 512² raster with `channels` values per pixel.
template <typename T>
std::vector<T> block(const std::vector<T>& src, int i, int j, int channels) {
  const size_t side = kTileSize, row = side * static_cast<size_t>(channels);
  std::vector<T> out(side * row);
  for (size_t y = 0; y < side; ++y) {
    const size_t from = ((static_cast<size_t>(j) * side + y) * 2 * side + static_cast<size_t>(i) * side) *
                        static_cast<size_t>(channels);
    std::copy_n(src.begin() + static_cast<std::ptrdiff_t>(from), row,
                out.begin() + static_cast<std::ptrdiff_t>(y * row));
  }
  return out;
}

}  // namespace

std::vector<HeightTile> splitHeightTile(const HeightTile& tile) {
  assert(tile.size == kLargeSourceTileSize);
  std::vector<HeightTile> out;
  for (const geo::TileId& c : geo::children(tile.id))
    out.push_back({c, kTileSize, block(tile.heights, c.x - 2 * tile.id.x, c.y - 2 * tile.id.y, 1)});
  return out;
}

std::vector<ColorTile> splitColorTile(const ColorTile& tile) {
  assert(tile.size == kLargeSourceTileSize);
  std::vector<ColorTile> out;
  for (const geo::TileId& c : geo::children(tile.id)) {
    ColorTile t;
    t.id = c;
    t.size = kTileSize;
    t.rgba = block(tile.rgba, c.x - 2 * tile.id.x, c.y - 2 * tile.id.y, 4);
    out.push_back(std::move(t));
  }
  return out;
}

Result<std::vector<HeightTile>> readSourceHeightTiles(XyzSource& source, const geo::TileId& id,
                                                      ElevationEncoding encoding) {
  auto bytes = source.read(id);
  if (!bytes) return bytes.error();
  if (!*bytes) return std::vector<HeightTile>();
  auto tile = decodeHeightTile(**bytes, id, encoding, kAnyTileSize, source.tileName(id));
  if (!tile) return tile.error();
  if (auto s = checkSize(source, id, tile->size); !s) return s.error();
  if (tile->size == kLargeSourceTileSize) return splitHeightTile(*tile);
  return std::vector<HeightTile>{std::move(*tile)};
}

Result<std::vector<ColorTile>> readSourceColorTiles(XyzSource& source, const geo::TileId& id) {
  auto bytes = source.read(id);
  if (!bytes) return bytes.error();
  if (!*bytes) return std::vector<ColorTile>();
  auto tile = decodeColorTile(**bytes, id, kAnyTileSize, source.tileName(id));
  if (!tile) return tile.error();
  if (auto s = checkSize(source, id, tile->size); !s) return s.error();
  if (tile->size == kLargeSourceTileSize) return splitColorTile(*tile);
  return std::vector<ColorTile>{std::move(*tile)};
}

Result<std::optional<int>> probeSourceTileSize(XyzSource& source, const std::vector<geo::TileId>& ids) {
  for (const geo::TileId& id : ids) {
    auto bytes = source.read(id);
    if (!bytes) return bytes.error();
    if (!*bytes) continue;
    auto tile = decodeColorTile(**bytes, id, kAnyTileSize, source.tileName(id));
    if (!tile) return tile.error();
    if (auto s = checkSize(source, id, tile->size); !s) return s.error();
    return std::optional<int>(tile->size);
  }
  return std::optional<int>();
}

}  // namespace vegstream::datasets
