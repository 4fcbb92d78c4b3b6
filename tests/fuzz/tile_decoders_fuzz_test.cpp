// Mutation test of the tile decoders (datasets/tile_codec.h) — the code the streamer's decode
// workers, `query`, `plants` and the importers' checks run on every tile file, local or fetched
// over HTTP. Small valid tiles (64 × 64 pixels of the synthetic terrain's heights and colours,
// datasets/synthetic_generator.h) are written by the dataset writers, then fed mutated
// (binary_mutations.h) to decodeHeightTile, decodeColorTile and decodeLandcoverTile (the
// one-channel codec NDVI shares) in process: every call must return a tile or a user error
// naming it — never throw, never crash.

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "datasets/landcover.h"
#include "datasets/synthetic_generator.h"
#include "datasets/tile_codec.h"
#include "tests/fuzz/binary_mutations.h"
#include "tests/fuzz/fuzz_support.h"

namespace vegstream::testing {
namespace {
namespace fs = std::filesystem;

constexpr uint64_t kSeed = 16;  // issue 16
constexpr int kMutations = 1200;
constexpr int kSide = 64;  // pixels: small, so a thousand decodes take well under a second
constexpr double kSpacingM = 20.0;

std::vector<uint8_t> fileBytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

datasets::HeightTile syntheticHeights() {
  const datasets::SyntheticTerrain terrain(7);
  datasets::HeightTile t;
  t.size = kSide;
  for (int y = 0; y < kSide; ++y)
    for (int x = 0; x < kSide; ++x)
      t.heights.push_back(static_cast<float>(terrain.heightM(x * kSpacingM, -y * kSpacingM)));
  t.heights[5] = NAN;  // one nodata pixel: alpha 0
  return t;
}

datasets::ColorTile syntheticColours() {
  const datasets::SyntheticTerrain terrain(7);
  datasets::ColorTile t;
  t.size = kSide;
  for (int y = 0; y < kSide; ++y)
    for (int x = 0; x < kSide; ++x) {
      const double e = x * kSpacingM, n = -y * kSpacingM, h = terrain.heightM(e, n);
      const double slope = std::atan(std::hypot(terrain.heightM(e + 1, n) - h, terrain.heightM(e, n + 1) - h));
      const auto c = terrain.color(e, n, h, slope);
      t.rgba.insert(t.rgba.end(), {c[0], c[1], c[2], 255});
    }
  return t;
}

// Feeds `decode` kMutations mutations of `valid` (made by `mutate`) and checks the tally.
// Nothing may be printed on stderr meanwhile: a corrupt tile is one error value, which the
// command line prints as its one line (libpng's own "libpng error: …" lines were a second).
template <typename Mutate, typename Decode>
void fuzz(const fs::path& dir, const std::vector<uint8_t>& valid, const char* reader, Mutate&& mutate,
          Decode&& decode) {
  ASSERT_TRUE(decode(valid).ok()) << reader << ": the unmutated tile must decode";
  const auto start = std::chrono::steady_clock::now();
  Outcomes tally;
  StderrCapture printed(dir / "stderr.txt");
  for (int i = 0; i < kMutations; ++i) {
    const ByteMutation m = mutate(valid, kSeed, static_cast<uint64_t>(i));
    expectValueOrError(
        [&] {
          auto r = decode(m.bytes);
          // A tile that decodes is whole: size × size samples.
          if (r.ok()) {
            EXPECT_GT(r->size, 0) << m.what;
          }
          return r;
        },
        std::string(reader) + " mutation " + std::to_string(i) + ": " + m.what, tally);
  }
  const std::string noise = printed.text();
  EXPECT_TRUE(noise.empty()) << reader << " printed on stderr:\n" << noise.substr(0, 2000);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  std::printf("%s: %d mutations, %d decoded, %d refused, %d threw, %.0f ms\n", reader, kMutations, tally.ok,
              tally.refused, tally.threw, ms);
  EXPECT_EQ(tally.threw, 0);
  EXPECT_GT(tally.refused, kMutations / 4) << "many mutations must break the tile";
}

TEST(TileDecodersFuzz, ElevationPng) {
  const fs::path dir = ownTestDir();
  const fs::path file = dir / "elevation.png";
  ASSERT_TRUE(datasets::writeHeightTile(file, syntheticHeights(), datasets::ElevationEncoding::Terrarium).ok());
  const auto decode = [](const std::vector<uint8_t>& b) {
    auto r = datasets::decodeHeightTile(b, {12, 2138, 1447}, datasets::ElevationEncoding::Terrarium,
                                        kSide, "fuzz/e.png");
    if (r.ok()) {
      EXPECT_EQ(r->heights.size(), static_cast<size_t>(r->size) * static_cast<size_t>(r->size));
    }
    return r;
  };
  fuzz(dir, fileBytes(file), "elevation tile (PNG)", mutatePng, decode);
}

TEST(TileDecodersFuzz, ImageryPng) {
  const fs::path dir = ownTestDir();
  const fs::path file = dir / "imagery.png";
  ASSERT_TRUE(datasets::writeColorTile(file, syntheticColours(), datasets::ImageryFormat::Png).ok());
  const auto decode = [](const std::vector<uint8_t>& b) {
    auto r = datasets::decodeColorTile(b, {12, 2138, 1447}, kSide, "fuzz/i.png");
    if (r.ok()) {
      EXPECT_EQ(r->rgba.size(), static_cast<size_t>(r->size) * static_cast<size_t>(r->size) * 4);
    }
    return r;
  };
  fuzz(dir, fileBytes(file), "imagery tile (PNG)", mutatePng, decode);
}

TEST(TileDecodersFuzz, ImageryJpeg) {
  const fs::path dir = ownTestDir();
  const fs::path file = dir / "imagery.jpg";
  ASSERT_TRUE(datasets::writeColorTile(file, syntheticColours(), datasets::ImageryFormat::Jpeg, 85).ok());
  const auto decode = [](const std::vector<uint8_t>& b) {
    auto r = datasets::decodeColorTile(b, {12, 2138, 1447}, kSide, "fuzz/i.jpg");
    if (r.ok()) {
      EXPECT_EQ(r->rgba.size(), static_cast<size_t>(r->size) * static_cast<size_t>(r->size) * 4);
    }
    return r;
  };
  fuzz(dir, fileBytes(file), "imagery tile (JPEG)", mutateBytes, decode);
}

TEST(TileDecodersFuzz, LandcoverPng) {
  const fs::path dir = ownTestDir();
  const fs::path file = dir / "landcover.png";
  datasets::LandcoverTile t;
  t.size = kSide;
  const datasets::SyntheticTerrain terrain(7);
  // WorldCover-like classes in bands of height, no data (0) in a corner.
  for (int y = 0; y < kSide; ++y) {
    for (int x = 0; x < kSide; ++x) {
      const int band = static_cast<int>(terrain.heightM(x * kSpacingM, -y * kSpacingM)) / 200 % 9;
      t.classes.push_back(static_cast<uint8_t>(x + y < 6 ? 0 : 10 + 10 * band));
    }
  }
  ASSERT_TRUE(datasets::writeLandcoverTile(file, t).ok());
  const auto decode = [](const std::vector<uint8_t>& b) {
    auto r = datasets::decodeLandcoverTile(b, {12, 2138, 1447}, "fuzz/l.png", kSide);
    if (r.ok()) {
      EXPECT_EQ(r->classes.size(), static_cast<size_t>(kSide) * static_cast<size_t>(kSide));
    }
    return r;
  };
  fuzz(dir, fileBytes(file), "landcover tile (PNG)", mutatePng, decode);
}

}  // namespace
}  // namespace vegstream::testing
