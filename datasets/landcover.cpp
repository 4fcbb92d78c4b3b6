// The landcover layer's pixels (landcover.h): its tiles through tile_codec's one-channel 8-bit
// PNG codec, nearest-neighbour sampling of a class raster, and the mode of a 2×2 block.

#include "datasets/landcover.h"

#include <array>
#include <cassert>
#include <cmath>

#include "datasets/message.h"
#include "datasets/tile_codec.h"

namespace vegstream::datasets {
namespace fs = std::filesystem;

Status writeLandcoverTile(const fs::path& path, const LandcoverTile& tile) {
  return writeGrey8Tile(path, tile.size, tile.classes);
}

Result<LandcoverTile> decodeLandcoverTile(std::span<const uint8_t> bytes, const geo::TileId& id,
                                          const std::string& nameForErrors, int expectedSize) {
  auto classes = decodeGrey8Tile(bytes, nameForErrors, expectedSize, "landcover");
  if (!classes) return classes.error();
  LandcoverTile t;
  t.id = id;
  t.size = expectedSize;
  t.classes = std::move(*classes);
  return t;
}

Result<LandcoverTile> readLandcoverTile(const fs::path& path, const geo::TileId& id, int expectedSize) {
  auto bytes = readTileFile(path);
  if (!bytes) return bytes.error();
  return decodeLandcoverTile(*bytes, id, path.string(), expectedSize);
}

uint8_t classCodeOf(const Raster& raster, float sample) {
  if (raster.isNodata(sample) || !(sample >= 1.0f && sample <= 255.0f) || std::floor(sample) != sample) return 0;
  return static_cast<uint8_t>(sample);
}

uint8_t nearestClass(const Raster& raster, glm::dvec2 pixel) {
  assert(raster.channels >= 1);
  // floor: the buffer pixel whose square [i, i + 1) × [j, j + 1) holds the point. NaN fails the
  // tests.
  const glm::dvec2 l = raster.local(pixel);
  if (!(l.x >= 0.0 && l.y >= 0.0 && l.x < raster.width && l.y < raster.height)) return 0;
  const int col = static_cast<int>(std::floor(l.x)), row = static_cast<int>(std::floor(l.y));
  return classCodeOf(raster, raster.at(col, row));
}

Status checkClassRaster(const Raster& raster) {
  if (raster.channels != 1)
    return makeError(ErrorKind::InvalidInput, concat("'", raster.path, "' has ", raster.channels,
                                                     " bands; a landcover raster has one band of class codes"));
  for (int row = 0; row < raster.height; ++row) {
    for (int col = 0; col < raster.width; ++col) {
      const float v = raster.at(col, row);
      if (raster.isNodata(v) || (v >= 0.0f && v <= 255.0f && std::floor(v) == v)) continue;
      // Whole-raster pixel coordinates of the sample (the window's origin and step applied).
      const glm::dvec2 at = raster.origin + glm::dvec2(col, row) * raster.step;
      return makeError(ErrorKind::InvalidInput, concat("'", raster.path, "' holds ", v, " at column ", at.x, ", row ",
                                                       at.y, "; a landcover raster holds integer class codes 0 … 255"));
    }
  }
  return {};
}

ClassHistogram classHistogram(const Raster& raster) {
  ClassHistogram h{};
  const size_t n = static_cast<size_t>(raster.width) * static_cast<size_t>(raster.height);
  const size_t stride = static_cast<size_t>(raster.channels);
  for (size_t i = 0; i < n; ++i) ++h[classCodeOf(raster, raster.samples[i * stride])];
  return h;
}

// Quadratic in the span's length, which is 4 in the pyramid: no table to clear per pixel.
uint8_t modeOfClasses(std::span<const uint8_t> classes) {
  uint8_t best = 0;
  size_t bestCount = 0;
  for (uint8_t c : classes) {
    if (c == 0) continue;
    size_t n = 0;
    for (uint8_t d : classes) n += d == c;
    if (n > bestCount || (n == bestCount && c < best)) {
      best = c;
      bestCount = n;
    }
  }
  return best;
}

}  // namespace vegstream::datasets
