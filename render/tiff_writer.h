#pragma once
// Writing one-channel 32-bit float images (the measurement AOVs, render/aov_image.h) as TIFF
// through OpenImageIO, atomically (temporary file + rename), as png_writer.h writes stills.

#include <cstdint>
#include <filesystem>
#include <span>

#include "core/result.h"

namespace vegstream::render {

// values: width × height floats, row-major from the top. An Io error names the path.
Status writeFloatTiff(const std::filesystem::path& path, uint32_t width, uint32_t height, std::span<const float> values);

}  // namespace vegstream::render
