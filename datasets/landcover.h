#pragma once
// The landcover layer's pixels (issue 40, item 4): `landcover/{z}/{x}/{y}.png` tiles, sampling a
// source class raster onto them, and the 2×2 reduction the pyramid builder uses.
//
// A landcover tile is an 8-bit grey PNG of tileSize × tileSize bytes, each the class code as
// the source stores it (landcover_classes.h: WorldCover 10 … 100, NLCD 11 … 95; codes a scheme
// does not know are kept as they are), 0 = no data. dataset.json's `landcover.encoding` is
// "class8". Classes are categories: they are never blended — sampled by nearest neighbour,
// reduced to lower zooms by the mode.

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "core/result.h"
#include "datasets/dataset_format.h"
#include "datasets/raster.h"
#include "datasets/landcover_classes.h"

namespace vegstream::datasets {

struct LandcoverTile {
  geo::TileId id;
  int size = kTileSize;
  std::vector<uint8_t> classes;  // size × size, row-major from the north, 0 = no data
  uint8_t at(int x, int y) const {
    return classes[static_cast<size_t>(y) * static_cast<size_t>(size) + static_cast<size_t>(x)];
  }
};

// Written atomically (temporary file + rename); errors name the path. tile.classes must hold
// size × size bytes.
Status writeLandcoverTile(const std::filesystem::path& path, const LandcoverTile& tile);
// A one-channel 8-bit PNG of expectedSize a side, checked in full first (png_check.h); anything
// else (RGB, 16-bit, JPEG, another size, a corrupt file) is InvalidInput naming `nameForErrors`.
Result<LandcoverTile> decodeLandcoverTile(std::span<const uint8_t> bytes, const geo::TileId& id,
                                          const std::string& nameForErrors, int expectedSize = kTileSize);
// The file's bytes through decodeLandcoverTile; a missing file is NotFound naming it.
Result<LandcoverTile> readLandcoverTile(const std::filesystem::path& path, const geo::TileId& id,
                                        int expectedSize = kTileSize);

// A source sample as a class code: an integer 1 … 255 is itself; nodata (Raster::isNodata),
// 0, and anything that is no such integer (negative, fractional, > 255) is 0.
uint8_t classCodeOf(const Raster& raster, float sample);

// The class of the source pixel under `pixel`: continuous pixel coordinates of the *whole*
// raster, (0, 0) its top-left corner, the centre of pixel (i, j) at (i + 0.5, j + 0.5), as
// GeoReference::transform and source_grid.h's samplers; `raster` is a window holding the point
// (Raster::local maps it into the window; a decimated window gives its own sample there).
// Nearest neighbour, never blended: the pixel whose square holds the point, a point on a shared
// edge going to the pixel right of / below it. Outside the window, or nodata there: 0.
// Channel 0 of the raster.
uint8_t nearestClass(const Raster& raster, glm::dvec2 pixel);

// A raster (window) that can be a landcover source: one channel, every sample nodata or an
// integer 0 … 255. InvalidInput otherwise, naming the raster's path and the first bad sample
// (value, whole-raster column and row).
Status checkClassRaster(const Raster& raster);
// Pixels per class code over the window's buffer (classCodeOf of channel 0; [0] = no data). The
// windows of the tiles overlap: count each source pixel once (one decimated read of the whole
// source), not the sum of the tiles' windows.
ClassHistogram classHistogram(const Raster& raster);

// The mode of the non-zero codes (the pyramid's 2×2 block), the smallest code among equally
// frequent ones; 0 when all are 0. Never a value that is not one of `classes`. Quadratic in
// the length: meant for small blocks.
uint8_t modeOfClasses(std::span<const uint8_t> classes);

}  // namespace vegstream::datasets
