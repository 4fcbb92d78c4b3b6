#pragma once
// Images the executable wrote. readRgb8: a PNG the executable wrote, as 8-bit RGB pixels (width × height × 3, row-major from the top),
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

// A one-channel float image (an AOV TIFF the executable wrote: scene/frame_aovs.h), width ×
// height floats; a test failure and an empty vector when it cannot be read or has another size.
inline std::vector<float> readFloat1(const std::filesystem::path& tif, int width, int height) {
  auto in = OIIO::ImageInput::open(tif.string());
  if (!in) {
    ADD_FAILURE() << "cannot read " << tif;
    return {};
  }
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width != width || spec.height != height || spec.nchannels != 1 || spec.format != OIIO::TypeDesc::FLOAT) {
    ADD_FAILURE() << tif << ": " << spec.width << "x" << spec.height << ", " << spec.nchannels << " channels of "
                  << spec.format.c_str() << "; expected " << width << "x" << height << ", 1 float channel";
    return {};
  }
  std::vector<float> v(static_cast<size_t>(width) * static_cast<size_t>(height));
  EXPECT_TRUE(in->read_image(0, 0, 0, 1, OIIO::TypeDesc::FLOAT, v.data()));
  return v;
}

}  // namespace vegstream::testing
