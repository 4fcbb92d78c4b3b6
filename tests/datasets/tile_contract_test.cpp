// Every tile checked against dataset.json before it is decoded (datasets/tile_codec.h) and only
// regular files read as tiles or dataset.json (core/regular_file.h): a tile of another size, a
// grey elevation tile, a FIFO, a directory or a link to /dev/zero where a tile or dataset.json
// should be, a 5 MB dataset.json, a broken one (line and column), one that smuggles control
// characters into the error, and a PROJJSON nested 100 000 deep — each an error value naming
// the file, in milliseconds.

#include <chrono>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sys/stat.h>

#include "datasets/dataset_format.h"
#include "datasets/tile_codec.h"
#include "tests/support/test_dirs.h"

namespace vegstream::datasets {
namespace {
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

fs::path freshDir(const std::string& name) {
  fs::path dir = testing::testOutputDir() / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

ColorTile colourTile(int size) {
  ColorTile t;
  t.size = size;
  t.rgba.assign(static_cast<size_t>(size) * static_cast<size_t>(size) * 4, 200);
  return t;
}

HeightTile heightTile(int size) {
  HeightTile t;
  t.size = size;
  t.heights.assign(static_cast<size_t>(size) * static_cast<size_t>(size), 1500.0f);
  return t;
}

std::string message(const Error& e) { return e.message; }

TEST(TileContract, AValidTileOfAnotherSizeIsRefusedBeforeAnyConsumer) {
  const fs::path d = freshDir("contract_size");
  ASSERT_TRUE(writeColorTile(d / "200.png", colourTile(200), ImageryFormat::Png).ok());
  ASSERT_TRUE(writeColorTile(d / "200.jpg", colourTile(200), ImageryFormat::Jpeg).ok());
  ASSERT_TRUE(writeHeightTile(d / "16.png", heightTile(16), ElevationEncoding::Terrarium).ok());
  for (const char* f : {"200.png", "200.jpg"}) {
    auto bad = readColorTile(d / f, {}, 256);
    ASSERT_FALSE(bad.ok()) << f;
    EXPECT_EQ(bad.error().kind, ErrorKind::InvalidInput);
    EXPECT_NE(message(bad.error()).find("is 200x200 pixels; dataset.json says tiles are 256 pixels a side"),
              std::string::npos)
        << message(bad.error());
    EXPECT_NE(message(bad.error()).find(f), std::string::npos) << message(bad.error());
    auto good = readColorTile(d / f, {}, 200);  // the same file in a dataset of 200-pixel tiles
    ASSERT_TRUE(good.ok()) << message(good.error());
    EXPECT_EQ(good->rgba.size(), 200u * 200u * 4u);
  }
  auto heights = readHeightTile(d / "16.png", {}, ElevationEncoding::Terrarium, 256);
  ASSERT_FALSE(heights.ok());
  EXPECT_NE(message(heights.error()).find("is 16x16 pixels"), std::string::npos) << message(heights.error());
  EXPECT_TRUE(readHeightTile(d / "16.png", {}, ElevationEncoding::Terrarium, 16).ok());
}

TEST(TileContract, ElevationTilesMustBeRgb) {
  const fs::path d = freshDir("contract_channels");
  const std::vector<uint8_t> grey(256 * 256, 90);
  ASSERT_TRUE(writeGrey8Tile(d / "grey.png", 256, grey).ok());
  auto r = readHeightTile(d / "grey.png", {}, ElevationEncoding::Terrarium, 256);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(message(r.error()).find("encoded heights need 8-bit RGB(A)"), std::string::npos) << message(r.error());
  EXPECT_TRUE(readColorTile(d / "grey.png", {}, 256).ok()) << "grey imagery is expanded to RGB";
}

TEST(TileContract, OnlyRegularFilesAreReadAsTilesAndAtOnce) {
  const fs::path d = freshDir("contract_files");
  ASSERT_EQ(::mkfifo((d / "fifo.png").c_str(), 0600), 0);
  fs::create_symlink("/dev/zero", d / "zero.png");
  fs::create_directories(d / "dir.png");
  const std::pair<const char*, const char*> cases[] = {
      {"fifo.png", "FIFO"}, {"zero.png", "is a device"}, {"dir.png", "is a directory"}};
  for (const auto& [file, says] : cases) {
    const auto t0 = Clock::now();
    auto c = readColorTile(d / file, {}, 256);
    auto h = readHeightTile(d / file, {}, ElevationEncoding::Terrarium, 256);
    EXPECT_LT(secondsSince(t0), 2.0) << file;
    ASSERT_FALSE(c.ok()) << file;
    ASSERT_FALSE(h.ok()) << file;
    EXPECT_EQ(c.error().kind, ErrorKind::InvalidInput) << file;
    EXPECT_NE(message(c.error()).find(says), std::string::npos) << message(c.error());
    EXPECT_NE(message(h.error()).find(file), std::string::npos) << message(h.error());
  }
  auto missing = readColorTile(d / "none.png", {}, 256);
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.error().kind, ErrorKind::NotFound);
}

// A dataset.json that parses: the hostile versions below change one thing of it.
nlohmann::json soundMeta(const fs::path& dir) {
  DatasetMeta m;
  m.name = "contract";
  m.bounds = {-113.1, 37.2, -113.0, 37.3};
  m.minZoom = 10;
  m.maxZoom = 12;
  m.imagery = ImageryFormat::Png;
  EXPECT_TRUE(writeDatasetMeta(dir, m).ok());
  std::ifstream in(dir / "dataset.json");
  return nlohmann::json::parse(in);
}

void write(const fs::path& file, const std::string& text) { std::ofstream(file, std::ios::binary) << text; }

TEST(DatasetJson, OnlyARegularFileUpToItsCeilingIsRead) {
  const fs::path d = freshDir("meta_files");
  const nlohmann::json sound = soundMeta(d);
  ASSERT_TRUE(readDatasetMeta(d).ok());
  fs::remove(d / "dataset.json");
  ASSERT_EQ(::mkfifo((d / "dataset.json").c_str(), 0600), 0);
  auto t0 = Clock::now();
  auto fifo = readDatasetMeta(d);
  EXPECT_LT(secondsSince(t0), 2.0);
  ASSERT_FALSE(fifo.ok());
  EXPECT_NE(message(fifo.error()).find("dataset.json: is a FIFO"), std::string::npos) << message(fifo.error());

  fs::remove(d / "dataset.json");
  fs::create_directories(d / "dataset.json");
  auto dir = readDatasetMeta(d);
  ASSERT_FALSE(dir.ok());
  EXPECT_NE(message(dir.error()).find("is a directory"), std::string::npos) << message(dir.error());

  fs::remove(d / "dataset.json");
  std::string padded = sound.dump(2);
  padded.insert(1, std::string(5 << 20, ' '));  // 5 MB of whitespace: still valid JSON
  write(d / "dataset.json", padded);
  t0 = Clock::now();
  auto big = readDatasetMeta(d);
  EXPECT_LT(secondsSince(t0), 2.0);
  ASSERT_FALSE(big.ok());
  EXPECT_EQ(big.error().kind, ErrorKind::InvalidInput);
  EXPECT_NE(message(big.error()).find("a dataset.json is at most 4194304 bytes"), std::string::npos)
      << message(big.error());
}

TEST(DatasetJson, ParseErrorsNameLineAndColumn) {
  const fs::path d = freshDir("meta_syntax");
  (void)soundMeta(d);
  write(d / "dataset.json", "{\n  \"name\": \"x\",\n  \"min_zoom\": 1 2\n}\n");
  auto r = readDatasetMeta(d);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().kind, ErrorKind::InvalidInput);
  EXPECT_NE(message(r.error()).find("is not valid JSON: line 3, column 17: syntax error while parsing object"), std::string::npos)
      << message(r.error());
}

bool hasControl(const std::string& s) {
  for (unsigned char c : s)
    if (c < 0x20 || c == 0x7f) return true;
  return false;
}

TEST(DatasetJson, ErrorsNeitherEchoControlCharactersNorLongValues) {
  const fs::path d = freshDir("meta_echo");
  nlohmann::json j = soundMeta(d);
  j["elevation"]["encoding"] = "\x1b]0;owned\x07\x1b[2J" + std::string(100000, 'x');
  write(d / "dataset.json", j.dump());
  auto r = readDatasetMeta(d);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(message(r.error()).find("elevation.encoding"), std::string::npos) << message(r.error());
  EXPECT_NE(message(r.error()).find("\\x1b]0;owned\\x07"), std::string::npos) << message(r.error());
  EXPECT_FALSE(hasControl(message(r.error()))) << message(r.error());
  EXPECT_LT(message(r.error()).size(), 400u);
}

TEST(DatasetJson, AProjjsonNestedDeeperThanAnyRealOneIsRefusedNotDumped) {
  const fs::path d = freshDir("meta_deep");
  nlohmann::json j = soundMeta(d);
  j["sources"] = nlohmann::json::array({nlohmann::json::object(
      {{"role", "elevation"}, {"path", "x.tif"}, {"crs", "x"}, {"description", "x"}, {"crs_projjson", "DEEP"}})});
  // Spliced in as text: nlohmann's own dump() of it would recurse 100 000 levels in the test too.
  const size_t depth = 100000;
  std::string text = j.dump();
  const std::string deep = "{\"a\":" + std::string(depth, '[') + std::string(depth, ']') + "}";
  text.replace(text.find("\"DEEP\""), 6, deep);
  write(d / "dataset.json", text);
  auto r = readDatasetMeta(d);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(message(r.error()).find("sources[0].crs_projjson' is nested more than 64 levels deep"), std::string::npos)
      << message(r.error());
}

}  // namespace
}  // namespace vegstream::datasets
