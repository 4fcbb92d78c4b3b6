// Landcover classes drive what a flight grows (issue 41, item 2), end to end: the Zion sample
// imported with a landcover layer that is built-up (ESA WorldCover 50) west of 113.02185° W and
// grassland (30) east of it, then `snapshot` 2 m above the Kolob clearing on that meridian,
// looking north along it (so west is the still's left half, east its right). The classify pass
// reads each imagery tile's classes (streamed beside it, render/terrain_pass.h's companion array):
// nothing grows on the left, grass on the right, and the validation layers stay silent.

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <OpenImageIO/imageio.h>

#include "tests/support/run_command.h"
#include "tests/support/test_dirs.h"
#include "tests/support/zion_sample.h"

namespace vegstream::testing {
namespace {
namespace fs = std::filesystem;

// The meridian is a texel edge of every zoom the dataset has (8 … 12: x = 48772 · 2^(z−10) / 256
// tiles), so the layer's classes — one per texel, 38 m at zoom 12 — split exactly there.
const std::string kPose = "--lat 37.457 --lon -113.02185 --alt 2 --heading 0 --pitch -10";

// A 2 × 2 ASCII grid of half-degree cells split at 113.02185° W: 50 (built-up) west, 30 (grassland) east.
fs::path writeSplitLandcover(const fs::path& dir) {
  const fs::path asc = dir / "landcover.asc";
  std::ofstream(asc) << "ncols 2\nnrows 2\nxllcorner -113.52185\nyllcorner 36.6\ncellsize 0.5\nNODATA_value 0\n"
                        "50 30\n50 30\n";
  return asc;
}

// Pixels of columns [x0, x1) whose RGB differs by more than 12 of 255 in a channel between two
// stills of the same size (the exposure, metered over the whole frame, moves every pixel a little).
double differingShare(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b, int width, int height, int x0,
                      int x1) {
  size_t n = 0;
  for (int y = 0; y < height; ++y)
    for (int x = x0; x < x1; ++x) {
      const size_t i = (static_cast<size_t>(y) * width + x) * 3;
      int d = 0;
      for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(int(a[i + c]) - int(b[i + c])));
      if (d > 12) ++n;
    }
  return double(n) / double(size_t(height) * size_t(x1 - x0));
}

std::vector<uint8_t> readRgb(const fs::path& file) {
  std::vector<uint8_t> px(320 * 180 * 3);
  auto in = OIIO::ImageInput::open(file.string());
  EXPECT_TRUE(in) << file;
  if (!in) return px;
  EXPECT_EQ(in->spec().width, 320);
  EXPECT_EQ(in->spec().height, 180);
  EXPECT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, px.data()));
  return px;
}

TEST(LandcoverSnapshot, BuiltUpGrowsNothingAndGrasslandGrowsGrass) {
  const fs::path dir = testOutputDir();
  const fs::path asc = writeSplitLandcover(dir);
  const auto dataset = zionImport("zion-landcover-split", "--radiometry reflectance --imagery-datetime "
                                                          "2015-08-18T17:58:00Z --landcover '" + asc.string() +
                                                          "' --landcover-crs EPSG:4326");
  ASSERT_TRUE(dataset.ok()) << dataset.error().message;
  const auto snap = [&](const fs::path& out, const std::string& extra) {
    return runVegstream("snapshot '" + dataset->string() + "' " + kPose + " --size 320x180 --validate --out '" +
                        out.string() + "' " + extra);
  };
  const fs::path with = dir / "plants.png", bare = dir / "bare.png";
  const auto a = snap(with, ""), b = snap(bare, "--no-plants");
  ASSERT_EQ(a.exitCode, 0) << a.err;
  ASSERT_EQ(b.exitCode, 0) << b.err;
  EXPECT_EQ(a.err.find("validation"), std::string::npos) << a.err;
  EXPECT_NE(a.err.find(" plants drawn"), std::string::npos) << a.err;
  const std::vector<uint8_t> pa = readRgb(with), pb = readRgb(bare);
  // Columns away from the meridian (the middle 16 px, where blades standing on it lean across).
  const double west = differingShare(pa, pb, 320, 180, 0, 152), east = differingShare(pa, pb, 320, 180, 168, 320);
  std::printf("pixels the plants change: west (built-up) %.4f, east (grassland) %.4f\n", west, east);
  EXPECT_LT(west, 0.002) << "built-up grows nothing";
  EXPECT_GT(east, 0.05) << "grassland grows grass";
}

}  // namespace
}  // namespace vegstream::testing
