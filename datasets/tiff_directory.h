#pragma once
// A minimal, bounded reader of a TIFF file's first image directory (IFD), for the tags that
// OpenImageIO 2.4 does not expose: the GeoTIFF tags and GDAL's nodata tag. OIIO still opens
// the file and decodes the pixels; this only reads a handful of small tag values.
//
// Classic TIFF and BigTIFF, either byte order. Every offset and count is checked against the
// file size before it is read, so a corrupt or hostile file gives an Error, never a crash or a
// huge allocation.

#include <cstdint>
#include <filesystem>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "core/result.h"

namespace vegstream::datasets {

// TIFF tag numbers this folder reads.
namespace tifftag {
inline constexpr uint16_t kImageWidth = 256;
inline constexpr uint16_t kImageLength = 257;
inline constexpr uint16_t kModelPixelScale = 33550;
inline constexpr uint16_t kModelTiepoint = 33922;
inline constexpr uint16_t kModelTransformation = 34264;
inline constexpr uint16_t kGeoKeyDirectory = 34735;
inline constexpr uint16_t kGeoDoubleParams = 34736;
inline constexpr uint16_t kGeoAsciiParams = 34737;
inline constexpr uint16_t kGdalNodata = 42113;
}  // namespace tifftag

struct TiffTagValue {
  uint16_t type = 0;            // TIFF field type (3 SHORT, 12 DOUBLE, 2 ASCII …)
  std::vector<double> numbers;  // numeric types, converted (rationals as num/den)
  std::string text;             // ASCII, with its NULs kept as written
};

struct TiffDirectory {
  std::map<uint16_t, TiffTagValue> tags;
  const TiffTagValue* find(uint16_t tag) const {
    auto it = tags.find(tag);
    return it == tags.end() ? nullptr : &it->second;
  }
};

// Reads the values of the `wanted` tags from the first IFD of `path` (other tags are skipped
// without reading their values). Errors are InvalidInput (not a TIFF, offsets past the end of
// the file) or Io, with the path in the message.
Result<TiffDirectory> readFirstTiffDirectory(const std::filesystem::path& path, std::span<const uint16_t> wanted);

}  // namespace vegstream::datasets
