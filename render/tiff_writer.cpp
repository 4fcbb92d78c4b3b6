// Float TIFF AOVs (tiff_writer.h): encoded in memory, then written atomically and checked.

#include "render/tiff_writer.h"

#include <cassert>

#include "core/atomic_file.h"
#include "core/encoded_image.h"

namespace vegstream::render {

Status writeFloatTiff(const std::filesystem::path& path, uint32_t width, uint32_t height, std::span<const float> values) {
  assert(values.size() == size_t{width} * height);
  OIIO::ImageSpec spec(static_cast<int>(width), static_cast<int>(height), 1, OIIO::TypeDesc::FLOAT);
  spec.attribute("compression", "zip");
  spec.attribute("oiio:ColorSpace", "Linear");
  auto bytes = encodeImage("tiff", spec, values.data(), path);
  if (!bytes) return bytes.error();
  return writeBytesAtomically(path, *bytes);
}

}  // namespace vegstream::render
