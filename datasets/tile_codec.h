#pragma once
// In-memory tiles and their encodings on disk (see dataset_format.h for the layout).
//
// Elevation encodings (metres):
//   terrarium:   h = R·256 + G + B/256 − 32768            (step 1/256 m ≈ 3.9 mm)
//   terrain-RGB: h = −10000 + (R·65536 + G·256 + B)·0.1   (step 0.1 m)
// encodeHeight rounds to the nearest step; decodeHeight(encodeHeight(h)) is within half a step.

#include <array>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "core/result.h"
#include "datasets/dataset_format.h"

namespace vegstream::datasets {

struct HeightTile {
  geo::TileId id;
  int size = kTileSize;
  std::vector<float> heights;  // size × size, row-major from the north, NaN = nodata
  float at(int x, int y) const {
    return heights[static_cast<size_t>(y) * static_cast<size_t>(size) + static_cast<size_t>(x)];
  }
};

struct ColorTile {
  geo::TileId id;
  int size = kTileSize;
  std::vector<uint8_t> rgba;  // size × size × 4, sRGB, alpha 0 = no data
  // The NDVI layer's tile over the same area (dataset_format.h): size × size bytes in the
  // encoding of ndviToByte, 0 = no NDVI there. Empty: the dataset has no NDVI layer, or no NDVI
  // tile here.
  std::vector<uint8_t> ndvi;
  // The landcover layer's class codes over the same area (landcover.h): size × size bytes, 0 = no
  // class there. Empty: no landcover layer, or no landcover tile here.
  std::vector<uint8_t> landcover;
};

// NDVI (−1 … 1) ↔ one byte: v = 128 + round(127 · ndvi), so 1 … 255 (step 1/127 ≈ 0.008), and
// 0 means "no NDVI". ndviFromByte(0) is NaN.
uint8_t ndviToByte(float ndvi);
float ndviFromByte(uint8_t v);

std::array<uint8_t, 3> encodeHeight(double heightM, ElevationEncoding encoding);
double decodeHeight(uint8_t r, uint8_t g, uint8_t b, ElevationEncoding encoding);
double encodingStepM(ElevationEncoding encoding);  // 1/256 or 0.1

// Written atomically (temporary file + rename). Errors name the path.
Status writeHeightTile(const std::filesystem::path& path, const HeightTile& tile, ElevationEncoding encoding);
Status writeColorTile(const std::filesystem::path& path, const ColorTile& tile, ImageryFormat format,
                      int jpegQuality = 90);

// The most pixels a side of any tile (dataset.json's tile_size stops here too): the decoders
// refuse a larger header before they inflate a row.
inline constexpr int kMaxTileSide = 4096;
// expectedSize for a tile that belongs to no dataset yet (an XYZ source's 256 or 512 tiles, whose
// importer checks the size itself): any square size up to kMaxTileSide.
inline constexpr int kAnyTileSize = 0;

// Decoding is bounded by what it checked: the image's header (for a PNG, before anything is
// inflated) must say square, `expectedSize` pixels a side (dataset.json's tile_size: pass
// DatasetMeta::tileSize, so a 200×200 tile in a dataset of 256 is refused, never over-read by a
// consumer), 1 to 4 channels (heights: 8-bit RGB or RGBA); only then are pixels allocated. A
// mismatching, corrupt or truncated tile is an InvalidInput error that names the path.
// Paletted and greyscale PNGs are expanded to RGB(A). The files are read through the checked
// opener (core/regular_file.h: only regular files, at most kTileFileCeiling).
Result<HeightTile> readHeightTile(const std::filesystem::path& path, const geo::TileId& id, ElevationEncoding encoding,
                                  int expectedSize);
Result<ColorTile> readColorTile(const std::filesystem::path& path, const geo::TileId& id, int expectedSize);

// The same decoders on a file's bytes already in memory (the streamer's decode workers; the
// read* functions above read the file and call these). The format comes from the bytes' magic
// number (PNG, JPEG, WebP); errors are InvalidInput and name `nameForErrors` (the tile's path or
// URL). Thread-safe: any number of threads may decode at once.
Result<HeightTile> decodeHeightTile(std::span<const uint8_t> bytes, const geo::TileId& id, ElevationEncoding encoding,
                                    int expectedSize, const std::string& nameForErrors);
Result<ColorTile> decodeColorTile(std::span<const uint8_t> bytes, const geo::TileId& id, int expectedSize,
                                  const std::string& nameForErrors);

// One-channel 8-bit layers (NDVI, landcover.h): `size` × `size` bytes written as a grey PNG
// (atomically; errors name the path), and read back only from such a PNG: anything else (RGB,
// 16-bit, JPEG, another size, a corrupt file) is InvalidInput naming `nameForErrors` and saying
// it is not a tile of the `layer` layer ("NDVI", "landcover").
Status writeGrey8Tile(const std::filesystem::path& path, int size, std::span<const uint8_t> bytes);
Result<std::vector<uint8_t>> decodeGrey8Tile(std::span<const uint8_t> bytes, const std::string& nameForErrors,
                                             int expectedSize, const char* layer);
// A tile file's bytes: NotFound naming it when it does not exist, Io when it cannot be read.
Result<std::vector<uint8_t>> readTileFile(const std::filesystem::path& path);

// NDVI tiles: 8-bit greyscale PNG of size × size bytes in the ndviToByte encoding. Writing
// takes tile.ndvi (size × size); decoding returns the size × size bytes (a PNG that is not
// one-channel 8-bit of the tile size is InvalidInput naming `nameForErrors`). The tile size is
// kTileSize unless a dataset.json says otherwise (its tile_size).
Status writeNdviTile(const std::filesystem::path& path, const ColorTile& tile);
Result<std::vector<uint8_t>> decodeNdviTile(std::span<const uint8_t> bytes, const geo::TileId& id,
                                            const std::string& nameForErrors, int expectedSize = kTileSize);
// The file's bytes through decodeNdviTile; a missing file is NotFound naming it.
Result<std::vector<uint8_t>> readNdviTile(const std::filesystem::path& path, const geo::TileId& id,
                                          int expectedSize = kTileSize);

}  // namespace vegstream::datasets
