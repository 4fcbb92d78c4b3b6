#include "render/png_writer.h"

#include <OpenImageIO/imageio.h>

#include "core/atomic_file.h"

namespace vegstream::render {

Status writePng(const std::filesystem::path& path, const ColorImage& image) {
  return writeFileAtomically(path, [&](const std::filesystem::path& tmp) -> Status {
    // The temporary name does not end in .png, so name the format explicitly.
    auto out = OIIO::ImageOutput::create("png");
    if (!out) return makeError(ErrorKind::Internal, "OpenImageIO has no PNG writer");
    OIIO::ImageSpec spec(static_cast<int>(image.width), static_cast<int>(image.height), 4, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:ColorSpace", "sRGB");
    if (!out->open(tmp.string(), spec))
      return makeError(ErrorKind::Io, "cannot write " + path.string() + ": " + out->geterror());
    const bool ok = out->write_image(OIIO::TypeDesc::UINT8, image.rgba.data());
    const bool closed = out->close();
    if (!ok || !closed) return makeError(ErrorKind::Io, "cannot write " + path.string() + ": " + out->geterror());
    return {};
  });
}

}  // namespace vegstream::render
