// Tile encodings on disk (tile_codec.h): heights ↔ terrarium / terrain-RGB pixels, and PNG /
// JPEG files through OpenImageIO. Every importer writes tiles here and every reader (streamer,
// query, the import tests) decodes them here, so the two directions cannot drift apart.

#include "datasets/tile_codec.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>
#include <memory>
#include <new>
#include <span>
#include <string>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "core/atomic_file.h"
#include "core/printable.h"
#include "core/regular_file.h"
#include "core/encoded_image.h"
#include "datasets/image_reader.h"
#include "datasets/message.h"
#include "datasets/png_check.h"

namespace vegstream::datasets {
namespace {
namespace fs = std::filesystem;
using OIIO::ImageInput;
using OIIO::ImageSpec;
using OIIO::TypeDesc;

constexpr int64_t kMaxCode = (int64_t{1} << 24) - 1;

std::string firstLine(std::string s) {
  if (auto nl = s.find('\n'); nl != std::string::npos) s.resize(nl);
  return s.empty() ? "unknown error" : s;
}

Error invalidTile(const std::string& name, const std::string& what) {
  std::string m = "tile '";
  m += name;
  m += "' ";
  m += what;
  return makeError(ErrorKind::InvalidInput, m);
}

// Encodes 8-bit pixels in memory and writes them atomically (encoded_image.h: no file writer
// of OIIO/libjpeg can fail silently or exit the process on a full disk).
Status writePixels(const fs::path& path, const char* format, int size, int channels, const uint8_t* pixels,
                   int jpegQuality) {
  ImageSpec spec(size, size, channels, TypeDesc::UINT8);
  if (std::string(format) == "jpeg") {
    std::string c = "jpeg:";
    c += std::to_string(jpegQuality);
    spec.attribute("Compression", c);
  } else {
    spec.attribute("png:compressionLevel", 3);  // 2.3× faster than 6, 3 % larger
  }
  auto bytes = encodeImage(format, spec, pixels, path);
  if (!bytes) return bytes.error();
  return writeBytesAtomically(path, *bytes);
}

// Reads an 8-bit tile as RGBA (greyscale and RGB expanded, paletted already expanded by OIIO).
struct Rgba8 {
  int size = 0;
  bool hadAlpha = false;
  int channels = 0;        // as stored (before the expansion to RGBA)
  bool eightBit = false;   // stored as 8-bit samples
  bool png = false;
  std::vector<uint8_t> rgba;
};

// OIIO picks its reader from the file name's extension; bytes in memory have none, so the
// magic number names the format (OIIO's name of its reader).
Result<const char*> sniffFormat(std::span<const uint8_t> bytes, const std::string& name) {
  static const uint8_t kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (bytes.size() >= 8 && std::memcmp(bytes.data(), kPng, 8) == 0) return "png";
  if (bytes.size() >= 3 && bytes[0] == 0xff && bytes[1] == 0xd8 && bytes[2] == 0xff) return "jpeg";
  if (bytes.size() >= 12 && std::memcmp(bytes.data(), "RIFF", 4) == 0 && std::memcmp(bytes.data() + 8, "WEBP", 4) == 0)
    return "webp";
  return invalidTile(name, concat("is not a PNG or JPEG image (", bytes.size(), " bytes of something else)"));
}

// The header against what the caller expects (dataset.json's tile_size, or any size up to
// kMaxTileSide when kAnyTileSize): checked before a pixel is allocated or decoded.
Status checkSpec(const ImageSpec& spec, const std::string& name, int expectedSize, bool requireEightBit) {
  if (spec.width != spec.height || spec.width <= 0 || spec.width > kMaxTileSide || spec.depth != 1)
    return invalidTile(name, concat("is ", spec.width, "x", spec.height,
                                    " pixels; a tile must be square and at most 4096 pixels a side"));
  if (expectedSize != kAnyTileSize && spec.width != expectedSize)
    return invalidTile(name, concat("is ", spec.width, "x", spec.height, " pixels; dataset.json says tiles are ",
                                    expectedSize, " pixels a side"));
  if (spec.nchannels < 1 || spec.nchannels > 4)
    return invalidTile(name, concat("has ", spec.nchannels, " channels; expected 1 to 4"));
  if (requireEightBit && spec.format != TypeDesc::UINT8)
    return invalidTile(name, concat("has ", spec.format.c_str(), " samples; encoded heights need 8-bit RGB(A)"));
  if (requireEightBit && spec.nchannels < 3)
    return invalidTile(name, concat("has ", spec.nchannels, " channel(s); encoded heights need 8-bit RGB(A)"));
  return {};
}

}  // namespace

// ImageInput::create of a bare format name only makes that reader, unopened (no probing of the
// others); it is then opened on the proxy, and a refusal is final.
std::unique_ptr<OIIO::ImageInput> openWithReaderOf(const char* format, OIIO::Filesystem::IOProxy& proxy,
                                                   std::string& error) {
  auto in = ImageInput::create(format);
  if (!in) {
    error = OIIO::geterror();
    if (error.empty()) error = concat("no ", format, " reader in OpenImageIO");
    return nullptr;
  }
  if (!in->supports("ioproxy")) {
    error = concat("OpenImageIO's ", format, " reader cannot read from memory");
    return nullptr;
  }
  in->set_ioproxy(&proxy);
  ImageSpec spec;
  if (!in->open(concat("tile.", format), spec)) {
    error = in->geterror();
    if (error.empty()) error = OIIO::geterror();
    return nullptr;
  }
  return in;
}

namespace {

Result<Rgba8> decodeRgba8Unguarded(std::span<const uint8_t> bytes, const std::string& name, bool requireEightBit,
                                   int expectedSize) {
  auto format = sniffFormat(bytes, name);
  if (!format) return format.error();
  // libpng prints its own "libpng error: …" line on stderr before OIIO reports a failure, which
  // would break the command line's one-line errors: a PNG is checked in full first, and libpng
  // sees only the chunks it needs of a sound file (png_check.h).
  std::vector<uint8_t> checkedBytes;
  if (std::strcmp(*format, "png") == 0) {
    const int maxSide = expectedSize == kAnyTileSize ? kMaxTileSide : std::clamp(expectedSize, 1, kMaxTileSide);
    auto checked = checkedPng(bytes, name, static_cast<uint32_t>(maxSide));
    if (!checked) return checked.error();
    checkedBytes = std::move(*checked);
    bytes = checkedBytes;
  }
  // The proxy only reads the caller's bytes; it must outlive the ImageInput (declared first).
  OIIO::Filesystem::IOMemReader proxy(bytes.data(), bytes.size());
  std::string openError;
  auto in = openWithReaderOf(*format, proxy, openError);
  if (!in) return invalidTile(name, concat("is not a readable PNG/JPEG: ", firstLine(openError)));
  const ImageSpec spec = in->spec();
  if (Status s = checkSpec(spec, name, expectedSize, requireEightBit); !s) return s.error();
  const int n = spec.nchannels;
  const size_t pixels = static_cast<size_t>(spec.width) * static_cast<size_t>(spec.height);
  std::vector<uint8_t> raw(pixels * static_cast<size_t>(n));
  // 8-bit samples are read as stored (TypeDesc::UNKNOWN, the same bytes): OIIO 2.4 reads "as
  // UINT8" through a 64 MB scratch buffer even when the file is UINT8 already, 0.5 ms a 32-pixel
  // tile (50 ms under ASan; found profiling the imagery_tile fuzz target). Other depths convert.
  const bool stored8 = spec.format == TypeDesc::UINT8 && spec.channelformats.empty();
  if (!in->read_image(0, 0, 0, n, stored8 ? TypeDesc(TypeDesc::UNKNOWN) : TypeDesc(TypeDesc::UINT8), raw.data()))
    return invalidTile(name, concat("is corrupt or truncated: ", firstLine(in->geterror())));
  in->close();
  Rgba8 t;
  t.size = spec.width;
  t.hadAlpha = n == 2 || n == 4;
  t.channels = n;
  t.eightBit = spec.format == TypeDesc::UINT8;
  t.png = std::strcmp(*format, "png") == 0;
  t.rgba.resize(pixels * 4);
  for (size_t i = 0; i < pixels; ++i) {
    const uint8_t* s = &raw[i * static_cast<size_t>(n)];
    uint8_t* d = &t.rgba[i * 4];
    if (n <= 2) {
      d[0] = d[1] = d[2] = s[0];
      d[3] = n == 2 ? s[1] : 255;
    } else {
      d[0] = s[0];
      d[1] = s[1];
      d[2] = s[2];
      d[3] = n == 4 ? s[3] : 255;
    }
  }
  return t;
}

// Any exception out of the image libraries (a corrupt file must never end the program, nor a
// decode worker) becomes an error naming the tile.
Result<Rgba8> decodeRgba8(std::span<const uint8_t> bytes, const std::string& name, bool requireEightBit,
                          int expectedSize) {
  try {
    return decodeRgba8Unguarded(bytes, name, requireEightBit, expectedSize);
  } catch (const std::bad_alloc&) {
    return makeError(ErrorKind::Io, concat("tile '", name, "': out of memory while decoding"));
  } catch (const std::exception& e) {
    return invalidTile(name, concat("is not a readable PNG/JPEG: ", firstLine(e.what())));
  }
}

// The whole file through the checked opener (core/regular_file.h): NotFound when it does not
// exist; InvalidInput when it is no regular file or past the tile ceiling; Io when a read fails.
Result<std::vector<uint8_t>> readFileBytes(const fs::path& path) {
  auto bytes = readRegularFileBytes(path, kTileFileCeiling);
  if (!bytes && bytes.error().kind == ErrorKind::NotFound) {
    std::string m = "tile '";
    m += printablePath(path);
    m += "' does not exist";
    return makeError(ErrorKind::NotFound, m);
  }
  return bytes;
}

}  // namespace

std::array<uint8_t, 3> encodeHeight(double heightM, ElevationEncoding encoding) {
  assert(std::isfinite(heightM));
  const double code =
      encoding == ElevationEncoding::Terrarium ? (heightM + 32768.0) * 256.0 : (heightM + 10000.0) * 10.0;
  int64_t n = static_cast<int64_t>(std::llround(code));
  n = n < 0 ? 0 : (n > kMaxCode ? kMaxCode : n);
  return {static_cast<uint8_t>(n >> 16), static_cast<uint8_t>((n >> 8) & 0xff), static_cast<uint8_t>(n & 0xff)};
}

double decodeHeight(uint8_t r, uint8_t g, uint8_t b, ElevationEncoding encoding) {
  if (encoding == ElevationEncoding::Terrarium) return r * 256.0 + g + b / 256.0 - 32768.0;
  return -10000.0 + (r * 65536.0 + g * 256.0 + b) * 0.1;
}

double encodingStepM(ElevationEncoding encoding) {
  return encoding == ElevationEncoding::Terrarium ? 1.0 / 256.0 : 0.1;
}

Status writeHeightTile(const fs::path& path, const HeightTile& tile, ElevationEncoding encoding) {
  assert(tile.size > 0 && tile.heights.size() == static_cast<size_t>(tile.size) * static_cast<size_t>(tile.size));
  std::vector<uint8_t> rgba(tile.heights.size() * 4, 0);
  for (size_t i = 0; i < tile.heights.size(); ++i) {
    const float h = tile.heights[i];
    if (!std::isfinite(h)) continue;  // nodata: RGBA 0, alpha 0
    const auto c = encodeHeight(h, encoding);
    rgba[i * 4 + 0] = c[0];
    rgba[i * 4 + 1] = c[1];
    rgba[i * 4 + 2] = c[2];
    rgba[i * 4 + 3] = 255;
  }
  return writePixels(path, "png", tile.size, 4, rgba.data(), 0);
}

Status writeColorTile(const fs::path& path, const ColorTile& tile, ImageryFormat format, int jpegQuality) {
  assert(tile.size > 0 && tile.rgba.size() == static_cast<size_t>(tile.size) * static_cast<size_t>(tile.size) * 4);
  assert(jpegQuality >= 1 && jpegQuality <= 100);
  if (format == ImageryFormat::Png) {
    return writePixels(path, "png", tile.size, 4, tile.rgba.data(), 0);
  }
  // JPEG has no alpha: nodata pixels become black, which readers see as "no data" only through
  // the elevation mask; imagery tiles themselves are written only where the source has data.
  std::vector<uint8_t> rgb(tile.rgba.size() / 4 * 3);
  for (size_t i = 0, n = tile.rgba.size() / 4; i < n; ++i) {
    const bool valid = tile.rgba[i * 4 + 3] != 0;
    for (size_t c = 0; c < 3; ++c) rgb[i * 3 + c] = valid ? tile.rgba[i * 4 + c] : 0;
  }
  return writePixels(path, "jpeg", tile.size, 3, rgb.data(), jpegQuality);
}

Result<HeightTile> decodeHeightTile(std::span<const uint8_t> bytes, const geo::TileId& id, ElevationEncoding encoding,
                                    int expectedSize, const std::string& nameForErrors) {
  auto px = decodeRgba8(bytes, nameForErrors, true, expectedSize);
  if (!px) return px.error();
  HeightTile t;
  t.id = id;
  t.size = px->size;
  t.heights.resize(static_cast<size_t>(t.size) * static_cast<size_t>(t.size));
  const auto& s = px->rgba;
  for (size_t i = 0; i < t.heights.size(); ++i) {
    t.heights[i] =
        s[i * 4 + 3] == 0 ? NAN : static_cast<float>(decodeHeight(s[i * 4], s[i * 4 + 1], s[i * 4 + 2], encoding));
  }
  return t;
}

Result<ColorTile> decodeColorTile(std::span<const uint8_t> bytes, const geo::TileId& id, int expectedSize,
                                  const std::string& nameForErrors) {
  auto px = decodeRgba8(bytes, nameForErrors, false, expectedSize);
  if (!px) return px.error();
  ColorTile t;
  t.id = id;
  t.size = px->size;
  t.rgba = std::move(px->rgba);
  return t;
}

uint8_t ndviToByte(float ndvi) {
  if (std::isnan(ndvi)) return 0;
  const long v = 128 + std::lround(127.0 * std::clamp(static_cast<double>(ndvi), -2.0, 2.0));
  return static_cast<uint8_t>(std::clamp(v, 1L, 255L));
}

float ndviFromByte(uint8_t v) { return v == 0 ? NAN : static_cast<float>(v - 128) / 127.0f; }

Status writeGrey8Tile(const fs::path& path, int size, std::span<const uint8_t> bytes) {
  assert(size > 0 && bytes.size() == static_cast<size_t>(size) * static_cast<size_t>(size));
  return writePixels(path, "png", size, 1, bytes.data(), 0);
}

Result<std::vector<uint8_t>> decodeGrey8Tile(std::span<const uint8_t> bytes, const std::string& nameForErrors,
                                             int expectedSize, const char* layer) {
  auto px = decodeRgba8(bytes, nameForErrors, false, expectedSize);
  if (!px) return px.error();
  // Only the grey PNG that writeGrey8Tile makes: an RGB or 16-bit image would be read as some
  // other quantity and silently give wrong values.
  if (!px->png || px->channels != 1 || !px->eightBit)
    return invalidTile(nameForErrors,
                       concat("is not a tile of the ", layer, " layer: expected a one-channel 8-bit PNG, found ",
                              px->png ? "a PNG" : "a JPEG/WebP", " with ", px->channels, " channel(s)",
                              px->eightBit ? "" : " of more than 8 bits"));
  if (px->size != expectedSize)
    return invalidTile(nameForErrors,
                       concat("is ", px->size, " pixels wide; ", layer, " tiles are ", expectedSize, " pixels wide"));
  std::vector<uint8_t> out(px->rgba.size() / 4);
  for (size_t i = 0; i < out.size(); ++i) out[i] = px->rgba[i * 4];
  return out;
}

Result<std::vector<uint8_t>> readTileFile(const fs::path& path) { return readFileBytes(path); }

Status writeNdviTile(const fs::path& path, const ColorTile& tile) { return writeGrey8Tile(path, tile.size, tile.ndvi); }

Result<std::vector<uint8_t>> decodeNdviTile(std::span<const uint8_t> bytes, const geo::TileId& id,
                                            const std::string& nameForErrors, int expectedSize) {
  (void)id;  // the bytes carry no position; kept for symmetry with the other decoders
  return decodeGrey8Tile(bytes, nameForErrors, expectedSize, "NDVI");
}

Result<std::vector<uint8_t>> readNdviTile(const fs::path& path, const geo::TileId& id, int expectedSize) {
  auto bytes = readFileBytes(path);
  if (!bytes) return bytes.error();
  return decodeNdviTile(*bytes, id, path.string(), expectedSize);
}

Result<HeightTile> readHeightTile(const fs::path& path, const geo::TileId& id, ElevationEncoding encoding,
                                  int expectedSize) {
  auto bytes = readFileBytes(path);
  if (!bytes) return bytes.error();
  return decodeHeightTile(*bytes, id, encoding, expectedSize, path.string());
}

Result<ColorTile> readColorTile(const fs::path& path, const geo::TileId& id, int expectedSize) {
  auto bytes = readFileBytes(path);
  if (!bytes) return bytes.error();
  return decodeColorTile(*bytes, id, expectedSize, path.string());
}

}  // namespace vegstream::datasets
