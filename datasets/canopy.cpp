// The canopy layer's pixels (canopy.h): 16-bit decimetre PNG tiles through OpenImageIO (checked by
// png_check.h before libpng sees them), and the check of a canopy height model's values.

#include "datasets/canopy.h"

#include <algorithm>
#include <cmath>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "core/atomic_file.h"
#include "core/encoded_image.h"
#include "datasets/image_reader.h"
#include "datasets/message.h"
#include "datasets/png_check.h"
#include "datasets/tile_codec.h"

namespace vegstream::datasets {
namespace fs = std::filesystem;
using OIIO::ImageInput;
using OIIO::ImageSpec;
using OIIO::TypeDesc;

namespace {

std::string firstLine(std::string s) {
  if (auto nl = s.find('\n'); nl != std::string::npos) s.resize(nl);
  return s.empty() ? "unknown error" : s;
}

Error badTile(const std::string& name, const std::string& what) {
  return makeError(ErrorKind::InvalidInput, concat("tile '", name, "' ", what));
}

// Whole-raster column and row of a window's sample, for messages.
std::string sampleText(const Raster& r, int col, int row, float v) {
  const glm::dvec2 p = r.origin + glm::dvec2(col, row) * r.step;
  return concat(v, " m at column ", static_cast<long>(p.x), ", row ", static_cast<long>(p.y));
}

}  // namespace

uint16_t canopyCodeOf(float heightM) {
  if (std::isnan(heightM)) return kNoCanopy;
  const long dm = std::lround(10.0 * std::clamp(static_cast<double>(heightM), 0.0, 6553.4));
  return static_cast<uint16_t>(std::clamp(dm, 0L, long{kNoCanopy} - 1));
}

float canopyHeightOf(uint16_t code) { return code == kNoCanopy ? NAN : static_cast<float>(code) * 0.1f; }

Status writeCanopyTile(const fs::path& path, const CanopyTile& tile) {
  ImageSpec spec(tile.size, tile.size, 1, TypeDesc::UINT16);
  spec.attribute("png:compressionLevel", 3);
  auto bytes = encodeImage("png", spec, tile.decimetres.data(), path);
  if (!bytes) return bytes.error();
  return writeBytesAtomically(path, *bytes);
}

Result<CanopyTile> decodeCanopyTile(std::span<const uint8_t> bytes, const geo::TileId& id,
                                    const std::string& nameForErrors, int expectedSize) {
  // Also refuses what is no PNG, and a header larger than the tile size before any inflate.
  auto checked = checkedPng(bytes, nameForErrors, static_cast<uint32_t>(std::max(expectedSize, 0)));
  if (!checked) return checked.error();
  OIIO::Filesystem::IOMemReader proxy(checked->data(), checked->size());
  std::string openError;
  auto in = openWithReaderOf("png", proxy, openError);  // the PNG reader only (image_reader.h)
  if (!in) return badTile(nameForErrors, concat("is not a readable PNG: ", firstLine(openError)));
  const ImageSpec spec = in->spec();
  if (spec.nchannels != 1 || spec.format != TypeDesc::UINT16)
    return badTile(nameForErrors, concat("is not a tile of the canopy layer: expected a one-channel 16-bit PNG, found ",
                                         spec.nchannels, " channel(s) of ", spec.format.c_str()));
  if (spec.width != expectedSize || spec.height != expectedSize)
    return badTile(nameForErrors, concat("is ", spec.width, "x", spec.height, " pixels; canopy tiles are ",
                                         expectedSize, " pixels wide"));
  CanopyTile t;
  t.id = id;
  t.size = expectedSize;
  t.decimetres.resize(static_cast<size_t>(expectedSize) * static_cast<size_t>(expectedSize));
  // Read as stored (checked UINT16 above): asking OIIO 2.4 for UINT16 goes through a 64 MB scratch
  // buffer even when no conversion is needed (tile_codec.cpp decodeRgba8Unguarded).
  if (!in->read_image(0, 0, 0, 1, TypeDesc::UNKNOWN, t.decimetres.data()))
    return badTile(nameForErrors, concat("is corrupt or truncated: ", firstLine(in->geterror())));
  return t;
}

Result<CanopyTile> readCanopyTile(const fs::path& path, const geo::TileId& id, int expectedSize) {
  auto bytes = readTileFile(path);
  if (!bytes) return bytes.error();
  return decodeCanopyTile(*bytes, id, path.string(), expectedSize);
}

Status checkCanopyRaster(const Raster& raster) {
  if (raster.channels != 1)
    return makeError(ErrorKind::InvalidInput,
                     concat("the canopy height model '", raster.path, "' has ", raster.channels,
                            " bands; a canopy height model has one band of heights above the ground"));
  for (int row = 0; row < raster.height; ++row)
    for (int col = 0; col < raster.width; ++col) {
      const float v = raster.at(col, row);
      if (raster.isNodata(v)) continue;
      if (v < kMinCanopyM)
        return makeError(ErrorKind::InvalidInput,
                         concat("the canopy height model '", raster.path, "' has a negative height (",
                                sampleText(raster, col, row, v), "): a canopy height model holds heights above the ",
                                "ground, never below ", kMinCanopyM, " m; mark missing data as nodata"));
      if (v > kMaxCanopyM)
        return makeError(ErrorKind::InvalidInput,
                         concat("the canopy height model '", raster.path, "' has a height of ",
                                sampleText(raster, col, row, v), ", taller than any tree (", kMaxCanopyM,
                                " m): are its values in centimetres or feet without the unit declared, or ",
                                "elevations rather than heights above the ground? Give heights in metres"));
    }
  return {};
}

fs::path canopyTilePath(const fs::path& datasetDir, const geo::TileId& id) {
  return datasetDir / "canopy" / std::to_string(id.z) / std::to_string(id.x) / concat(id.y, ".png");
}

}  // namespace vegstream::datasets
