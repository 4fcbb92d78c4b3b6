#pragma once
// Encoding pixels into an image file's bytes in memory through OpenImageIO (an IOVecOutput
// proxy), so that the encoder's status is all that can fail here and the bytes then go to disk
// through the checked, atomic writer (core/atomic_file.h). OpenImageIO's file writers do not
// report a failed write (a full disk gave a truncated PNG and success), and libjpeg's default
// error handler calls exit(1) on one; neither can happen on a memory buffer.

#include <cstdint>
#include <filesystem>
#include <vector>

#include <OpenImageIO/imageio.h>

#include "core/result.h"

namespace vegstream {

// `format`: an OIIO format name ("png", "tiff", "jpeg"); `spec` holds size, channels, sample
// type and attributes; `pixels` are in spec.format. Io error naming `nameForErrors` on failure.
Result<std::vector<uint8_t>> encodeImage(const char* format, const OIIO::ImageSpec& spec, const void* pixels,
                                         const std::filesystem::path& nameForErrors);

}  // namespace vegstream
