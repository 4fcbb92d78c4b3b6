// Tile codec: height encodings round-trip within half a step, nodata stays a mask, and tile
// files written through OpenImageIO decode to the same heights / colours.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "datasets/tile_codec.h"
#include "tests/support/test_dirs.h"

namespace vegstream::datasets {
namespace {
namespace fs = std::filesystem;

fs::path tmpDir(const std::string& name) {
  const fs::path d = vegstream::testing::testOutputDir() / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

class EncodingRoundTrip : public ::testing::TestWithParam<ElevationEncoding> {};

TEST_P(EncodingRoundTrip, WithinHalfAStepFromTrenchToSummit) {
  const ElevationEncoding enc = GetParam();
  const double step = encodingStepM(enc);
  std::mt19937_64 rng(7);
  // terrain-RGB starts at −10 000 m (code 0); terrarium reaches the deepest trench.
  std::uniform_real_distribution<double> h(enc == ElevationEncoding::Terrarium ? -11000.0 : -10000.0, 9000.0);
  double worst = 0.0;
  for (int i = 0; i < 100000; ++i) {
    const double v = h(rng);
    const auto c = encodeHeight(v, enc);
    worst = std::max(worst, std::abs(decodeHeight(c[0], c[1], c[2], enc) - v));
  }
  EXPECT_LE(worst, 0.5 * step + 1e-9);
}

INSTANTIATE_TEST_SUITE_P(Both, EncodingRoundTrip,
                         ::testing::Values(ElevationEncoding::Terrarium, ElevationEncoding::TerrainRgb));

TEST(TileCodec, KnownCodes) {
  // terrarium: 0 m = 128,0,0; terrain-RGB: 0 m = 100000 × 0.1 → 1,134,160.
  EXPECT_EQ(encodeHeight(0.0, ElevationEncoding::Terrarium), (std::array<uint8_t, 3>{128, 0, 0}));
  EXPECT_EQ(encodeHeight(0.0, ElevationEncoding::TerrainRgb), (std::array<uint8_t, 3>{1, 134, 160}));
  EXPECT_DOUBLE_EQ(decodeHeight(128, 0, 0, ElevationEncoding::Terrarium), 0.0);
  EXPECT_NEAR(decodeHeight(1, 134, 160, ElevationEncoding::TerrainRgb), 0.0, 1e-9);
  EXPECT_DOUBLE_EQ(encodingStepM(ElevationEncoding::Terrarium), 1.0 / 256.0);
  EXPECT_DOUBLE_EQ(encodingStepM(ElevationEncoding::TerrainRgb), 0.1);
}

TEST_P(EncodingRoundTrip, TileFileKeepsHeightsAndNodataMask) {
  const ElevationEncoding enc = GetParam();
  HeightTile t;
  t.id = {12, 758, 1608};
  t.heights.resize(256 * 256);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> h(-500.f, 4000.f);
  int nodata = 0;
  for (size_t i = 0; i < t.heights.size(); ++i) {
    t.heights[i] = (i % 17 == 0) ? NAN : h(rng);
    nodata += std::isnan(t.heights[i]);
  }
  // One file per encoding: ctest may run the parameterised cases at the same time.
  const fs::path p = tmpDir("heights") / ("t" + std::to_string(static_cast<int>(enc)) + ".png");
  ASSERT_TRUE(writeHeightTile(p, t, enc));
  auto back = readHeightTile(p, t.id, enc, kTileSize);
  ASSERT_TRUE(back) << back.error().message;
  ASSERT_EQ(back->size, 256);
  int backNodata = 0;
  double worst = 0.0;
  for (size_t i = 0; i < t.heights.size(); ++i) {
    if (std::isnan(back->heights[i])) {
      ++backNodata;
      EXPECT_TRUE(std::isnan(t.heights[i]));
      continue;
    }
    worst = std::max(worst, std::abs(double(back->heights[i]) - double(t.heights[i])));
  }
  EXPECT_EQ(backNodata, nodata);
  // + float rounding of a 4 km height (2.4e-4 m).
  EXPECT_LE(worst, 0.5 * encodingStepM(enc) + 5e-4);
}

TEST(TileCodec, ColourPngIsLosslessAndJpegClose) {
  ColorTile t;
  t.rgba.resize(256 * 256 * 4);
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x) {
      uint8_t* p = &t.rgba[(size_t(y) * 256 + size_t(x)) * 4];
      p[0] = uint8_t(x);
      p[1] = uint8_t(y);
      p[2] = 90;
      p[3] = 255;
    }
  const fs::path d = tmpDir("colour");
  ASSERT_TRUE(writeColorTile(d / "a.png", t, ImageryFormat::Png));
  auto png = readColorTile(d / "a.png", t.id, kTileSize);
  ASSERT_TRUE(png);
  EXPECT_EQ(png->rgba, t.rgba);
  ASSERT_TRUE(writeColorTile(d / "a.jpg", t, ImageryFormat::Jpeg, 90));
  auto jpg = readColorTile(d / "a.jpg", t.id, kTileSize);
  ASSERT_TRUE(jpg);
  double sum = 0.0;
  for (size_t i = 0; i < t.rgba.size(); ++i) sum += std::abs(int(jpg->rgba[i]) - int(t.rgba[i]));
  EXPECT_LT(sum / double(t.rgba.size()), 2.0);  // a smooth gradient at quality 90
}

TEST(TileCodec, CorruptAndMissingTilesNameTheFile) {
  const fs::path d = tmpDir("corrupt");
  HeightTile t;
  t.heights.assign(256 * 256, 100.f);
  ASSERT_TRUE(writeHeightTile(d / "good.png", t, ElevationEncoding::Terrarium));
  const auto size = fs::file_size(d / "good.png");
  fs::copy_file(d / "good.png", d / "cut.png");
  fs::resize_file(d / "cut.png", size / 2);
  auto cut = readHeightTile(d / "cut.png", {}, ElevationEncoding::Terrarium, kTileSize);
  ASSERT_FALSE(cut);
  EXPECT_EQ(cut.error().kind, ErrorKind::InvalidInput);
  EXPECT_NE(cut.error().message.find("cut.png"), std::string::npos) << cut.error().message;
  // One flipped byte inside the pixel data: caught by the chunk CRC before libpng prints.
  fs::copy_file(d / "good.png", d / "flip.png");
  {
    std::fstream f(d / "flip.png", std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(static_cast<std::streamoff>(size / 2));
    f.put('\x5a');
  }
  auto flip = readHeightTile(d / "flip.png", {}, ElevationEncoding::Terrarium, kTileSize);
  ASSERT_FALSE(flip);
  EXPECT_NE(flip.error().message.find("CRC"), std::string::npos) << flip.error().message;
  std::ofstream(d / "text.png") << "not a png";
  auto text = readHeightTile(d / "text.png", {}, ElevationEncoding::Terrarium, kTileSize);
  ASSERT_FALSE(text);
  EXPECT_NE(text.error().message.find("text.png"), std::string::npos);
  auto missing = readColorTile(d / "none.png", {}, kTileSize);
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().kind, ErrorKind::NotFound);
}

TEST(TileCodec, GrandCanyonTerrariumAndTerrainRgbAgree) {
  const fs::path root = VEGSTREAM_DATASETS_DIR "/grandcanyon-xyz";
  auto a = readHeightTile(root / "terrarium/12/759/1608.png", {12, 759, 1608}, ElevationEncoding::Terrarium, kTileSize);
  auto b =
      readHeightTile(root / "terrain-rgb/12/759/1608.png", {12, 759, 1608}, ElevationEncoding::TerrainRgb, kTileSize);
  ASSERT_TRUE(a) << a.error().message;
  ASSERT_TRUE(b) << b.error().message;
  ASSERT_EQ(a->size, b->size);
  // The two files are not the same raster re-encoded: they differ per pixel by metres (median
  // |Δ| 3.1 m, max 76 m, no pixel shift explains it), so only their mean difference agrees.
  double signedSum = 0.0, lo = 1e9, hi = -1e9;
  for (size_t i = 0; i < a->heights.size(); ++i) {
    signedSum += double(a->heights[i]) - double(b->heights[i]);
    lo = std::min(lo, double(b->heights[i]));
    hi = std::max(hi, double(b->heights[i]));
  }
  EXPECT_LE(std::abs(signedSum / double(a->heights.size())), 1.0);
  EXPECT_GE(lo, 439.0 - 0.1);
  EXPECT_LE(hi, 2184.0 + 0.1);
}

// A full disk while a tile is written (RLIMIT_FSIZE in a child, SIGXFSZ ignored: write(2) gets
// EFBIG as it gets ENOSPC on a full disk): the tile already there stays byte-identical, the
// error names it and the reason (not "corrupt"), no temporary is left, and the process is not
// ended by libjpeg's default error handler (the JPEG is encoded in memory, datasets/encoded_image.h).
TEST(TileCodec, FullDiskKeepsTheOldTileAndSaysWhy) {
  const fs::path dir = testing::testOutputDir();
  ColorTile tile;
  tile.size = 256;
  tile.rgba.resize(256 * 256 * 4);
  for (size_t i = 0; i < tile.rgba.size(); ++i) tile.rgba[i] = i % 4 == 3 ? 255 : static_cast<uint8_t>((i * 7) % 251);
  for (const ImageryFormat format : {ImageryFormat::Jpeg, ImageryFormat::Png}) {
    const fs::path file = dir / (format == ImageryFormat::Jpeg ? "tile.jpg" : "tile.png");
    ASSERT_TRUE(writeColorTile(file, tile, format).ok());
    std::ifstream in(file, std::ios::binary);
    const std::string old((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    int fds[2];
    ASSERT_EQ(::pipe(fds), 0);
    const pid_t pid = ::fork();
    if (pid == 0) {
      ::signal(SIGXFSZ, SIG_IGN);
      const rlimit limit{1024, 1024};
      ::setrlimit(RLIMIT_FSIZE, &limit);
      const Status s = writeColorTile(file, tile, format);
      const std::string message = s ? std::string() : s.error().message;
      if (::write(fds[1], message.data(), message.size()) < 0) ::_exit(3);
      ::_exit(s ? 0 : 1);
    }
    ::close(fds[1]);
    std::string message;
    char buf[256];
    for (ssize_t n; (n = ::read(fds[0], buf, sizeof buf)) > 0;) message.append(buf, static_cast<size_t>(n));
    ::close(fds[0]);
    int status = 0;
    ::waitpid(pid, &status, 0);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 1) << status << " " << message;
    EXPECT_NE(message.find(file.string()), std::string::npos) << message;
    EXPECT_NE(message.find("file too large"), std::string::npos) << message;
    EXPECT_EQ(message.find("corrupt"), std::string::npos) << message;
    std::ifstream again(file, std::ios::binary);
    EXPECT_EQ(std::string((std::istreambuf_iterator<char>(again)), std::istreambuf_iterator<char>()), old);
    for (const auto& e : fs::directory_iterator(dir))
      EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
    EXPECT_TRUE(readColorTile(file, tile.id, tile.size).ok());
  }
}

}  // namespace
}  // namespace vegstream::datasets
