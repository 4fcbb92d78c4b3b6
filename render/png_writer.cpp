// Read-back frames as PNG (png_writer.h): encoded in memory, then written atomically and checked.

#include "render/png_writer.h"

#include "core/atomic_file.h"
#include "core/encoded_image.h"

namespace vegstream::render {

Result<std::vector<uint8_t>> encodePng(const ColorImage& image, const std::filesystem::path& nameForErrors) {
  OIIO::ImageSpec spec(static_cast<int>(image.width), static_cast<int>(image.height), 4, OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:ColorSpace", "sRGB");
  return encodeImage("png", spec, image.rgba.data(), nameForErrors);
}

Status writePng(const std::filesystem::path& path, const ColorImage& image) {
  auto bytes = encodePng(image, path);
  if (!bytes) return bytes.error();
  return writeBytesAtomically(path, *bytes);
}

}  // namespace vegstream::render
