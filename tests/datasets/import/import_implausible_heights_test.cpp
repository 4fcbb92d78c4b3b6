// Heights no terrain on Earth has (below −11 000 m or above 9 000 m) are nodata, with a
// warning that counts them — never drawn as spikes, never clamped.

#include <gtest/gtest.h>

#include "datasets/dataset_format.h"
#include "datasets/tile_codec.h"
#include "import_test_util.h"
#include "tests/datasets/tiny_tiff.h"

namespace vegstream::datasets {
namespace {
using namespace vegstream::datasets::test;

TEST(ImportImplausibleHeights, BecomeNodataWithACountedWarning) {
  const fs::path dir = importTmp("implausible");
  // 8 × 8 Float32 DEM, 0.001° pixels at (−113.0, 37.3), heights 1000 … 1630 m, except
  // three spikes to 20 000 m and one pit to −20 000 m.
  std::vector<float> heights;
  for (int i = 0; i < 64; ++i) heights.push_back(1000.0f + 10.0f * static_cast<float>(i));
  heights[9] = heights[27] = heights[45] = 20000.0f;
  heights[50] = -20000.0f;
  TinyImage img;
  img.width = img.height = 8;
  img.bits = 32;
  img.sampleFormat = 3;
  img.pixels = pixelBytes(heights);
  img.extra = {doubles(33550, {0.001, 0.001, 0}), doubles(33922, {0, 0, 0, -113.0, 37.3, 0}),
               shorts(34735, {1, 1, 0, 3, 1024, 0, 1, 2, 1025, 0, 1, 1, 2048, 0, 1, 4326})};
  const fs::path dem = dir / "spiky.tif";
  writeTinyTiff(dem, img);

  const fs::path out = dir / "ds";
  const auto r = vegstream::testing::runVegstream("import --dem '" + dem.string() + "' --out '" + out.string() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("4 heights outside"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("spiky.tif"), std::string::npos) << r.err;
  auto meta = readDatasetMeta(out);
  ASSERT_TRUE(meta.ok()) << meta.error().message;
  EXPECT_LE(meta->maxHeightM, 1630.0 + 1.0);
  EXPECT_GE(meta->minHeightM, 1000.0 - 1.0);
}

}  // namespace
}  // namespace vegstream::datasets
