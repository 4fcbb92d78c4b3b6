#pragma once
// Writing read-back frames as PNG through OpenImageIO, atomically (temporary file + rename).

#include <filesystem>

#include "core/result.h"
#include "render/frame_types.h"

namespace vegstream::render {

Status writePng(const std::filesystem::path& path, const ColorImage& image);

}  // namespace vegstream::render
