#include "render/tiff_writer.h"

#include <cassert>

#include <OpenImageIO/imageio.h>

#include "core/atomic_file.h"

namespace vegstream::render {

Status writeFloatTiff(const std::filesystem::path& path, uint32_t width, uint32_t height, std::span<const float> values) {
  assert(values.size() == size_t{width} * height);
  return writeFileAtomically(path, [&](const std::filesystem::path& tmp) -> Status {
    // The temporary name does not end in .tif, so name the format explicitly.
    auto out = OIIO::ImageOutput::create("tiff");
    if (!out) return makeError(ErrorKind::Internal, "OpenImageIO has no TIFF writer");
    OIIO::ImageSpec spec(static_cast<int>(width), static_cast<int>(height), 1, OIIO::TypeDesc::FLOAT);
    spec.attribute("compression", "zip");
    spec.attribute("oiio:ColorSpace", "Linear");
    if (!out->open(tmp.string(), spec))
      return makeError(ErrorKind::Io, "cannot write " + path.string() + ": " + out->geterror());
    const bool ok = out->write_image(OIIO::TypeDesc::FLOAT, values.data());
    const bool closed = out->close();
    if (!ok || !closed) return makeError(ErrorKind::Io, "cannot write " + path.string() + ": " + out->geterror());
    return {};
  });
}

}  // namespace vegstream::render
