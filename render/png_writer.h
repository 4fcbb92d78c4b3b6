#pragma once
// Writing read-back frames as PNG through OpenImageIO, atomically (temporary file + rename).

#include <cstdint>
#include <filesystem>
#include <vector>

#include "core/result.h"
#include "render/frame_types.h"

namespace vegstream::render {

Status writePng(const std::filesystem::path& path, const ColorImage& image);

// The PNG file's bytes (in memory; errors name `nameForErrors`).
Result<std::vector<uint8_t>> encodePng(const ColorImage& image, const std::filesystem::path& nameForErrors);

}  // namespace vegstream::render
