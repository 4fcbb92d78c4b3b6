// Mutation test of the GDAL raster source (datasets/raster_source.h), which `vegstream import`
// runs on user files (GDAL's GTiff driver and libtiff underneath): a tiny valid GeoTIFF (2 × 2 samples, WGS 84 keys, tests/datasets/tiny_tiff.h)
// mutated byte by byte (binary_mutations.h) and read from a file in this test's own directory.
// Every read must return a raster or a user error naming the file — never throw, never crash —
// and nothing may be printed on stderr (GDAL's and libtiff's own warnings would be a second line
// beside the command line's one message). A source that opens is read as the importer does: a
// window (at most 64 × 64 here), so a header claiming billions of pixels costs nothing.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "datasets/raster_source.h"
#include "tests/datasets/tiny_tiff.h"
#include "tests/fuzz/binary_mutations.h"
#include "tests/fuzz/fuzz_support.h"

namespace vegstream::testing {
namespace {
namespace fs = std::filesystem;

constexpr uint64_t kSeed = 16;  // issue 16
constexpr int kMutations = 1000;

TEST(RasterSourceFuzz, MutatedGeoTiffsAreRastersOrErrors) {
  const fs::path dir = ownTestDir();
  datasets::test::TinyImage img;
  img.pixels = datasets::test::pixelBytes(std::vector<uint16_t>{1, 2, 3, 4});
  img.extra = {datasets::test::doubles(33550, {10, 10, 0}), datasets::test::doubles(33922, {0, 0, 0, 100, 50, 0}),
               datasets::test::shorts(34735, {1, 1, 0, 3, 1024, 0, 1, 2, 1025, 0, 1, 1, 2048, 0, 1, 4326})};
  const fs::path validFile = dir / "valid.tif";
  datasets::test::writeTinyTiff(validFile, img);
  ASSERT_TRUE(datasets::readWholeRaster(validFile.string()).ok()) << "the unmutated file must read";
  std::ifstream in(validFile, std::ios::binary);
  const std::vector<uint8_t> valid((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());

  const fs::path file = dir / "mutated.tif";
  const auto start = std::chrono::steady_clock::now();
  Outcomes tally;
  StderrCapture printed(dir / "stderr.txt");
  for (int i = 0; i < kMutations; ++i) {
    const ByteMutation m = mutateBytes(valid, kSeed, static_cast<uint64_t>(i));
    std::ofstream(file, std::ios::binary | std::ios::trunc)
        .write(reinterpret_cast<const char*>(m.bytes.data()), static_cast<std::streamsize>(m.bytes.size()));
    expectValueOrError(
        [&] {
          auto r = [&]() -> Result<datasets::Raster> {
            auto src = datasets::RasterSource::open({file.string()}, {});
            if (!src) return src.error();
            return src->read(0, 0, std::min(src->width(), 64), std::min(src->height(), 64));
          }();
          if (r.ok()) {
            EXPECT_EQ(r->samples.size(),
                      static_cast<size_t>(r->width) * static_cast<size_t>(r->height) * static_cast<size_t>(r->channels))
                << m.what;
          } else {
            EXPECT_NE(r.error().message.find(file.string()), std::string::npos) << m.what << ": " << r.error().message;
          }
          return r;
        },
        "GeoTIFF mutation " + std::to_string(i) + ": " + m.what, tally);
  }
  const std::string noise = printed.text();
  EXPECT_TRUE(noise.empty()) << "printed on stderr:\n" << noise.substr(0, 2000);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  std::printf("GeoTIFF: %d mutations, %d read, %d refused, %d threw, %.0f ms\n", kMutations, tally.ok, tally.refused,
              tally.threw, ms);
  EXPECT_EQ(tally.threw, 0);
  EXPECT_GT(tally.refused, kMutations / 4);
}

}  // namespace
}  // namespace vegstream::testing
