// In-memory image encoding (encoded_image.h).

#include "core/encoded_image.h"

#include <OpenImageIO/filesystem.h>

#include <string>

namespace vegstream {

namespace {
std::string firstLineOf(std::string s) {
  if (auto nl = s.find('\n'); nl != std::string::npos) s.resize(nl);
  return s.empty() ? std::string("unknown error") : s;
}
}  // namespace

Result<std::vector<uint8_t>> encodeImage(const char* format, const OIIO::ImageSpec& spec, const void* pixels,
                                         const std::filesystem::path& nameForErrors) {
  const auto fail = [&](const std::string& why) -> Error {
    return makeError(ErrorKind::Io, "cannot encode '" + nameForErrors.string() + "' as " + format + ": " + why);
  };
  auto out = OIIO::ImageOutput::create(format);
  if (!out) return fail(firstLineOf(OIIO::geterror()));
  if (!out->supports("ioproxy")) return fail("OpenImageIO's writer cannot write to memory");
  std::vector<uint8_t> bytes;
  OIIO::Filesystem::IOVecOutput memory(bytes);
  OIIO::Filesystem::IOProxy* proxy = &memory;
  OIIO::ImageSpec withProxy = spec;
  withProxy.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
  const bool ok = out->open(nameForErrors.string(), withProxy) && out->write_image(spec.format, pixels);
  const bool closed = out->close();
  const std::string error = out->geterror();  // read even on success: TIFF leaves a harmless Exif note
  if (!ok || !closed) return fail(firstLineOf(error));
  if (bytes.empty()) return fail("the encoder wrote nothing");
  return bytes;
}

}  // namespace vegstream
