#pragma once
// The canopy layer's pixels (issue 41 item 3, `import --canopy-height`): a canopy height model
// (heights of vegetation above the ground, metres) as `canopy/{z}/{x}/{y}.png` tiles.
//
// A canopy tile is a one-channel 16-bit PNG of tileSize × tileSize samples, each the height in
// decimetres (0 … 65534 = 0 … 6553.4 m), kNoCanopy (65535) = no data. dataset.json's
// `canopy.encoding` is "decimetre16" and `canopy.zoom` the zoom the CHM was sampled at (the one
// keeping its own pixels, about 1 m); lower zooms hold the pyramid (each pixel the highest of its
// 2 × 2 children: a tree top seen from afar stays as tall).
//
// A CHM is checked before it is used (checkCanopyRaster): heights below kMinCanopyM (noise about
// the ground is allowed) and above kMaxCanopyM (taller than any tree: a unit problem, or
// elevations rather than heights above the ground) are refused, naming the file and the sample.

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "core/result.h"
#include "datasets/dataset_format.h"
#include "datasets/raster.h"

namespace vegstream::datasets {

inline constexpr uint16_t kNoCanopy = 65535;
inline constexpr float kMinCanopyM = -1.0f;   // below: not a height above the ground
inline constexpr float kMaxCanopyM = 130.0f;  // above: taller than any tree (the tallest stand ~116 m)

struct CanopyTile {
  geo::TileId id;
  int size = kTileSize;
  std::vector<uint16_t> decimetres;  // size × size, row-major from the north, kNoCanopy = no data
  uint16_t at(int x, int y) const {
    return decimetres[static_cast<size_t>(y) * static_cast<size_t>(size) + static_cast<size_t>(x)];
  }
};

// Height (m) → code: NaN → kNoCanopy; otherwise round(10 h) clamped to 0 … 65534 (the small
// negative heights of noise about the ground become 0).
uint16_t canopyCodeOf(float heightM);
// Code → height (m); NaN for kNoCanopy.
float canopyHeightOf(uint16_t code);

// Written atomically (temporary file + rename); errors name the path.
Status writeCanopyTile(const std::filesystem::path& path, const CanopyTile& tile);
// A one-channel 16-bit PNG of expectedSize a side, checked in full first (png_check.h); anything
// else is InvalidInput naming `nameForErrors`.
Result<CanopyTile> decodeCanopyTile(std::span<const uint8_t> bytes, const geo::TileId& id,
                                    const std::string& nameForErrors, int expectedSize = kTileSize);
// The file's bytes through decodeCanopyTile; a missing file is NotFound naming it.
Result<CanopyTile> readCanopyTile(const std::filesystem::path& path, const geo::TileId& id,
                                  int expectedSize = kTileSize);

// A raster (window, metres: RasterSource with heights on has converted feet) that can be a CHM:
// one channel, every valid sample within kMinCanopyM … kMaxCanopyM. InvalidInput otherwise,
// naming the raster's path, the problem and the first bad sample (value, column and row of the
// whole raster); above kMaxCanopyM the message suggests the unit.
Status checkCanopyRaster(const Raster& raster);

std::filesystem::path canopyTilePath(const std::filesystem::path& datasetDir, const geo::TileId& id);

}  // namespace vegstream::datasets
