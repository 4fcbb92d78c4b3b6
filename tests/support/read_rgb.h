#pragma once
// A PNG the executable wrote, as 8-bit RGB pixels (width × height × 3, row-major from the top),
// for the tests that compare frames pixel by pixel; a test failure and an empty vector when the
// file cannot be read.

#include <filesystem>
#include <vector>

#include <gtest/gtest.h>
#include <OpenImageIO/imageio.h>

namespace vegstream::testing {

inline std::vector<unsigned char> readRgb8(const std::filesystem::path& png, int width, int height) {
  std::vector<unsigned char> rgb(static_cast<size_t>(width) * static_cast<size_t>(height) * 3);
  auto in = OIIO::ImageInput::open(png.string());
  if (!in) {
    ADD_FAILURE() << "cannot read " << png;
    return {};
  }
  EXPECT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, rgb.data()));
  return rgb;
}

}  // namespace vegstream::testing
