// Hostile tiles in a sound dataset (issue 42 items 1, 2): valid PNGs of the wrong size, a FIFO, a
// link to /dev/zero and a directory where tiles should be. The streamer fails such a tile (one
// warning, its parent drawn instead) within seconds; the snapshot's mosaic refuses it with one
// error naming it instead of reading past it; a dataset whose coarsest zoom already overflows
// the mosaic's ceiling, or whose tile_size the streamer does not draw, is refused before
// anything is allocated.

#include <chrono>
#include <sstream>

#include <gtest/gtest.h>
#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>
#include <sys/stat.h>

#include "datasets/tile_codec.h"
#include "streaming/dataset_snapshot.h"
#include "streaming/local_tile_source.h"
#include "streaming/open_tile_source.h"
#include "streaming_fixture.h"

namespace vegstream::streaming::test {
namespace {
using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// A logger whose lines the test reads.
struct CapturedLog {
  std::ostringstream text;
  Logger log = std::make_shared<spdlog::logger>("captured", std::make_shared<spdlog::sinks::ostream_sink_mt>(text));
  int linesMentioning(const std::string& what) const {
    std::istringstream in(text.str());
    int n = 0;
    for (std::string line; std::getline(in, line);) n += line.find(what) != std::string::npos;
    return n;
  }
};

datasets::ColorTile colourTile(int size) {
  datasets::ColorTile t;
  t.size = size;
  t.rgba.assign(static_cast<size_t>(size) * static_cast<size_t>(size) * 4, 90);
  return t;
}

StreamingOptions smallOptions() {
  StreamingOptions o;
  o.decodeThreads = 2;
  o.maxRequestsInFlight = 8;
  return o;
}

using HostileTiles = SyntheticDataset;

// What each hostile file does to the streamer: failed (undecodable for a tile of the wrong size,
// not arrived for what is no regular file), warned once, the parent drawn.
TEST_F(HostileTiles, TheStreamerFailsEachHostileTileOnceAndDrawsItsParent) {
  ASSERT_TRUE(meta().imagery.has_value());
  const fs::path copy = testTmp("hostile_streamer");
  fs::copy(dir(), copy, fs::copy_options::recursive);
  const auto keys = tilesAt(copy, meta(), TileLayer::Imagery, meta().maxZoom);
  ASSERT_GE(keys.size(), 4u);
  const TileKey wrongSize = keys[0], fifo = keys[1], zero = keys[2], directory = keys[3];
  const auto pathOf = [&](const TileKey& k) { return copy / datasetRelativePath(k, meta()); };
  // A valid 200 × 200 PNG where the dataset says 256: the upload copied 256 × 256 × 4 from it.
  fs::remove(pathOf(wrongSize));
  ASSERT_TRUE(datasets::writeColorTile(pathOf(wrongSize), colourTile(200), datasets::ImageryFormat::Png).ok());
  for (const TileKey& k : {fifo, zero, directory}) fs::remove(pathOf(k));
  ASSERT_EQ(::mkfifo(pathOf(fifo).c_str(), 0600), 0);
  fs::create_symlink("/dev/zero", pathOf(zero));
  fs::create_directories(pathOf(directory));

  CapturedLog captured;
  auto source = std::make_shared<LocalTileSource>(copy);
  TileStreamer s(source, meta(), smallOptions(), captured.log);
  std::vector<TileWant> wants;
  for (const TileKey& k : {wrongSize, fifo, zero, directory}) {
    wants.push_back({k, 2.0, false});
    wants.push_back({parentOf(k), 1.0, false});
  }
  const auto t0 = Clock::now();
  s.settle(wants, 0.0);
  EXPECT_LT(secondsSince(t0), 5.0) << "no read may block or run until memory is gone";
  for (const TileKey& k : {wrongSize, fifo, zero, directory}) {
    EXPECT_EQ(s.state(k), TileState::Failed) << toString(k);
    const auto why = s.failure(k);
    ASSERT_TRUE(why) << toString(k);
    const auto found = s.findResident(k);
    ASSERT_TRUE(found.tile) << toString(k);
    EXPECT_EQ(found.levelsUp, 1) << toString(k);
    EXPECT_EQ(captured.linesMentioning(toString(k)), 1) << captured.text.str();
  }
  EXPECT_TRUE(s.failure(wrongSize)->undecodable);
  EXPECT_NE(s.failure(wrongSize)->message.find("is 200x200 pixels; dataset.json says tiles are 256"), std::string::npos)
      << s.failure(wrongSize)->message;
  EXPECT_NE(s.failure(fifo)->message.find("FIFO"), std::string::npos) << s.failure(fifo)->message;
  EXPECT_NE(s.failure(zero)->message.find("is a device"), std::string::npos) << s.failure(zero)->message;
  EXPECT_NE(s.failure(directory)->message.find("is a directory"), std::string::npos) << s.failure(directory)->message;
  // Failed is final: nothing is asked again.
  s.update(wants, 100.0);
  EXPECT_EQ(s.frameStats().requestsIssued, 0u);
  fs::remove_all(copy);
}

// 16 × 16 elevation tiles: the mosaic read them as 256 × 256 (heights from outside the tile).
TEST_F(HostileTiles, TheSnapshotMosaicRefusesATileOfAnotherSize) {
  const fs::path copy = testTmp("hostile_mosaic");
  fs::copy(dir(), copy, fs::copy_options::recursive);
  datasets::HeightTile small;
  small.size = 16;
  small.heights.assign(16 * 16, 1.8e3f);
  for (int z = meta().minZoom; z <= meta().maxZoom; ++z)
    for (const TileKey& k : tilesAt(copy, meta(), TileLayer::Height, z))
      ASSERT_TRUE(
          datasets::writeHeightTile(copy / datasetRelativePath(k, meta()), small, meta().elevationEncoding).ok());
  LocalTileSource source(copy);
  auto heights = loadGroundHeights(source, meta(), {});
  ASSERT_FALSE(heights.ok()) << "zoom " << heights->zoom;
  EXPECT_EQ(heights.error().kind, ErrorKind::InvalidInput);
  EXPECT_NE(heights.error().message.find("is 16x16 pixels; dataset.json says tiles are 256"), std::string::npos)
      << heights.error().message;
  EXPECT_NE(heights.error().message.find("elevation/"), std::string::npos) << heights.error().message;
  fs::remove_all(copy);
}

// min_zoom = max_zoom = 16 over a wide box: the mosaic took 3.3 GB (bad_alloc at zoom 18).
TEST_F(HostileTiles, AMosaicPastItsCeilingIsRefusedBeforeAllocating) {
  datasets::DatasetMeta m = meta();
  m.minZoom = m.maxZoom = 16;
  m.bounds = {-113.5, 37.0, -112.5, 37.6};
  LocalTileSource source(dir());
  const auto t0 = Clock::now();
  auto heights = loadGroundHeights(source, m, {});
  EXPECT_LT(secondsSince(t0), 1.0);
  ASSERT_FALSE(heights.ok());
  EXPECT_EQ(heights.error().kind, ErrorKind::InvalidInput);
  EXPECT_NE(heights.error().message.find("at its min_zoom 16"), std::string::npos) << heights.error().message;
  EXPECT_NE(heights.error().message.find("the ground mosaic stops at 1000000 pixels"), std::string::npos)
      << heights.error().message;
}

TEST_F(HostileTiles, ATileSizeTheStreamerDoesNotDrawIsRefusedWithDatasetJson) {
  const fs::path copy = testTmp("hostile_tile_size");
  fs::create_directories(copy);
  datasets::DatasetMeta m = meta();
  m.tileSize = 512;
  ASSERT_TRUE(datasets::writeDatasetMeta(copy, m).ok());
  auto source = openTileSource(copy.string(), {});
  ASSERT_TRUE(source.ok()) << source.error().message;
  auto read = readMetaFrom(**source);
  ASSERT_FALSE(read.ok());
  EXPECT_NE(read.error().message.find("field 'tile_size' is 512; vegstream streams tiles of 256 pixels only"),
            std::string::npos)
      << read.error().message;
  fs::remove_all(copy);
}

}  // namespace
}  // namespace vegstream::streaming::test
