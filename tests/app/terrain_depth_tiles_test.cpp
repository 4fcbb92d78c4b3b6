// The terrain rasterised in compute hands its depth to the depth attachment only where plants or
// trees may be drawn (render/terrain_depth_handover.h). The real executable records two flights
// over the imported Zion sample at 160 × 90, 4× MSAA, with every tile handed over (`all`), with
// the tiles under the marks (`vegetation`, the default) and with the tiles left out set to the
// near plane (`checked`: a plant or a tree drawn over one would vanish). The saved frames must be
// the same byte for byte, the marks must leave tiles out, and validation must stay silent.

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/run_command.h"
#include "tests/support/test_dirs.h"
#include "tests/support/zion_sample.h"

namespace vegstream {
namespace {
namespace fs = std::filesystem;
using testing::runVegstream;

constexpr uint64_t kTiles = 20 * 12;  // 8 × 8 tiles of a 160 × 90 frame

// The repository's flight `name` (this file is tests/app/…; __FILE__ is relative to the build
// directory, the parent of the executable's app/, when the compiler was given a relative path).
fs::path flightPath(const std::string& name) {
  fs::path self(__FILE__);
  if (self.is_relative()) self = fs::path(VEGSTREAM_EXE).parent_path().parent_path() / self;
  return (self.parent_path().parent_path().parent_path() / "flight" / "paths" / (name + ".json")).lexically_normal();
}

// The repository's flight `name` with its clock `factor` times as fast (the same route and poses,
// fewer frames at 1 fps), written once into this test's directory.
fs::path fasterFlight(const std::string& name, double factor) {
  std::ifstream in(flightPath(name));
  nlohmann::json flight = nlohmann::json::parse(in);
  for (auto& key : flight.at("keyframes")) key["t"] = key.at("t").get<double>() / factor;
  const fs::path out = testing::testOutputDir() / (name + "_faster.json");
  std::ofstream(out) << flight.dump(2);
  return out;
}

// Per frame: the tiles handed over per pixel plus per sample.
std::vector<uint64_t> tilesWritten(const fs::path& recording) {
  std::ifstream f(recording / "frames.csv");
  std::string line, cell;
  std::getline(f, line);
  std::vector<std::string> header;
  for (std::stringstream ss(line); std::getline(ss, cell, ',');) header.push_back(cell);
  size_t pixel = header.size(), edge = header.size();
  for (size_t i = 0; i < header.size(); ++i) {
    if (header[i] == "terrain_depth_tiles") pixel = i;
    if (header[i] == "terrain_depth_edge_tiles") edge = i;
  }
  EXPECT_LT(pixel, header.size());
  EXPECT_LT(edge, header.size());
  std::vector<uint64_t> out;
  while (std::getline(f, line)) {
    std::vector<std::string> cells;
    for (std::stringstream ss(line); std::getline(ss, cell, ',');) cells.push_back(cell);
    if (pixel >= cells.size() || edge >= cells.size()) continue;
    out.push_back(std::stoull(cells[pixel]) + std::stoull(cells[edge]));
  }
  return out;
}

// `flight` at 1 fps with every `every`-th frame saved, the terrain rasterised in compute, `mode`'s tiles.
fs::path record(const fs::path& dataset, const fs::path& flight, int every, const std::string& mode) {
  const fs::path out = testing::testOutputDir() / (flight.stem().string() + "_" + mode);
  fs::remove_all(out);
  const auto r =
      runVegstream("record '" + dataset.string() + "' --path '" + flight.string() + "' --out '" + out.string() +
                   "' --size 160x90 --msaa 4 --fps 1 --frames-every " + std::to_string(every) +
                   " --no-plots --validate --terrain-shading compute --terrain-depth-tiles " + mode);
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.err.find("alidation"), std::string::npos) << r.err;
  return out;
}

std::vector<std::string> frames(const fs::path& recording) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(recording / "frames"))
    if (e.path().extension() == ".png") names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

void expectSameFrames(const fs::path& a, const fs::path& b) {
  const auto names = frames(a);
  ASSERT_GE(names.size(), 8u);
  EXPECT_EQ(frames(b), names);
  for (const std::string& n : names)
    EXPECT_EQ(testing::readWhole(a / "frames" / n), testing::readWhole(b / "frames" / n)) << n << " differs";
}

void expectMarksLeaveTilesOut(const fs::path& flight, int every, bool vegetationToo) {
  auto zion = testing::zionSampleDataset();
  ASSERT_TRUE(zion.ok()) << zion.error().message;
  const fs::path all = record(*zion, flight, every, "all"), checked = record(*zion, flight, every, "checked");
  expectSameFrames(all, checked);
  const auto allTiles = tilesWritten(all), checkedTiles = tilesWritten(checked);
  ASSERT_GE(allTiles.size(), 31u) << flight.stem() << " at 1 fps";
  ASSERT_EQ(checkedTiles.size(), allTiles.size());
  uint64_t written = 0;
  for (size_t i = 0; i < allTiles.size(); ++i) {
    EXPECT_EQ(allTiles[i], kTiles) << "frame " << i << ": every tile";
    EXPECT_LE(checkedTiles[i], kTiles) << "frame " << i;
    written += checkedTiles[i];
  }
  EXPECT_LT(written, allTiles.size() * kTiles * 9 / 10) << "the marks leave tiles out";
  if (!vegetationToo) return;
  const fs::path vegetation = record(*zion, flight, every, "vegetation");
  expectSameFrames(all, vegetation);
  EXPECT_EQ(tilesWritten(vegetation), checkedTiles);
}

// Low over grass, slickrock and scattered conifers: the marks leave most of the rock out.
TEST(TerrainDepthTiles, BenchmarkFlightDrawsTheSameFramesWithFewerTiles) {
  expectMarksLeaveTilesOut(flightPath("benchmark-30s"), 3, true);
}

// Canyon walls and a few trees, then the canyon floor: trees near and far. The flight's 301 s
// three times as fast: 101 frames a recording at 1 fps, every stretch of the route still
// in them (the whole flight took 200 s of the suite's time on the 2-core machine).
TEST(TerrainDepthTiles, CanyonFlightDrawsTheSameFramesWithFewerTiles) {
  expectMarksLeaveTilesOut(fasterFlight("canyon-run", 3.0), 10, false);
}

}  // namespace
}  // namespace vegstream
