#pragma once
// Helpers of the import tests: run `vegstream import` into a fresh directory, and read an
// imported dataset back through the tile codec and the geo tile maths (bilinear heights,
// nearest colour) without depending on the query command.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <string>

#include "datasets/dataset_format.h"
#include "datasets/tile_codec.h"
#include "geo/xyz_tiles.h"
#include "tests/support/run_command.h"
#include "tests/support/test_dirs.h"

namespace vegstream::datasets::test {

namespace fs = std::filesystem;

inline fs::path importTmp(const std::string& name) {
  const fs::path d = vegstream::testing::testOutputDir() / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

inline std::string samples() { return VEGSTREAM_DATASETS_DIR; }

// Entries of a directory (0 when it does not exist).
inline int entriesIn(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return 0;
  int n = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++n;
  return n;
}

// A refused import (the bad-input tests): `import ARGS --out PARENT/OUT` run in a fresh PARENT.
struct ImportRun {
  fs::path parent;  // holds --out and nothing else
  fs::path out;
  vegstream::testing::CommandResult result;
};

inline ImportRun runImportIn(const std::string& parentName, const std::string& args,
                             const std::string& outName = "out") {
  ImportRun c;
  c.parent = importTmp(parentName);
  c.out = c.parent / outName;
  c.result = vegstream::testing::runVegstream("import " + args + " --out " + c.out.string());
  return c;
}

// The contract of every bad-input case: exit 2, one line on stderr naming `names` and saying
// `what`, nothing on stdout, and nothing left at or beside --out (PARENT holds its
// `entriesBefore` entries made by the test's setup).
inline void expectRefused(const ImportRun& c, const std::string& names, const std::string& what,
                          int entriesBefore = 0) {
  EXPECT_EQ(c.result.exitCode, 2) << c.result.err;
  EXPECT_EQ(vegstream::testing::countLines(c.result.err), 1) << c.result.err;
  EXPECT_NE(c.result.err.find(names), std::string::npos) << c.result.err;
  EXPECT_NE(c.result.err.find(what), std::string::npos) << c.result.err;
  EXPECT_EQ(entriesIn(c.parent), entriesBefore) << "left behind in " << c.parent;
  if (entriesBefore == 0) {
    EXPECT_FALSE(fs::exists(c.out));
  }
  EXPECT_TRUE(c.result.out.empty()) << c.result.out;
}

// Reads a dataset's max-zoom tiles on demand.
class DatasetSampler {
 public:
  DatasetSampler(fs::path dir, DatasetMeta meta) : dir_(std::move(dir)), meta_(std::move(meta)) {}
  const DatasetMeta& meta() const { return meta_; }

  // Bilinear height at lon/lat from the max zoom; NaN where any neighbour is nodata.
  double height(double lonDeg, double latDeg) {
    const int z = meta_.maxZoom, n = meta_.tileSize;
    const glm::dvec2 t = geo::lonLatToTileXY({lonDeg, latDeg}, z);
    const double gx = t.x * n - 0.5, gy = t.y * n - 0.5;
    const long x0 = static_cast<long>(std::floor(gx)), y0 = static_cast<long>(std::floor(gy));
    const double fx = gx - static_cast<double>(x0), fy = gy - static_cast<double>(y0);
    const double v00 = pixel(x0, y0), v10 = pixel(x0 + 1, y0), v01 = pixel(x0, y0 + 1), v11 = pixel(x0 + 1, y0 + 1);
    return (v00 * (1 - fx) + v10 * fx) * (1 - fy) + (v01 * (1 - fx) + v11 * fx) * fy;
  }

  // Colour of the max-zoom imagery pixel holding lon/lat; nullopt where no tile / no data.
  std::optional<std::array<int, 3>> colour(double lonDeg, double latDeg) {
    const int z = meta_.maxZoom, n = meta_.tileSize;
    const glm::dvec2 t = geo::lonLatToTileXY({lonDeg, latDeg}, z);
    const geo::TileId id{z, static_cast<int>(t.x), static_cast<int>(t.y)};
    auto it = colours_.find(id);
    if (it == colours_.end()) {
      auto c = readColorTile(imageryTilePath(dir_, id, *meta_.imagery), id, meta_.tileSize);
      it = colours_.emplace(id, c ? std::optional<ColorTile>(std::move(*c)) : std::nullopt).first;
    }
    if (!it->second) return std::nullopt;
    const int px = static_cast<int>((t.x - id.x) * n), py = static_cast<int>((t.y - id.y) * n);
    const uint8_t* p =
        &it->second->rgba[(static_cast<size_t>(py) * static_cast<size_t>(n) + static_cast<size_t>(px)) * 4];
    if (p[3] == 0) return std::nullopt;
    return std::array<int, 3>{p[0], p[1], p[2]};
  }

 private:
  double pixel(long gx, long gy) {
    const int n = meta_.tileSize;
    const geo::TileId id{meta_.maxZoom, static_cast<int>(gx / n), static_cast<int>(gy / n)};
    auto it = heights_.find(id);
    if (it == heights_.end()) {
      auto h = readHeightTile(elevationTilePath(dir_, id), id, meta_.elevationEncoding, meta_.tileSize);
      it = heights_.emplace(id, h ? std::optional<HeightTile>(std::move(*h)) : std::nullopt).first;
    }
    if (!it->second) return NAN;
    return it->second->at(static_cast<int>(gx % n), static_cast<int>(gy % n));
  }

  fs::path dir_;
  DatasetMeta meta_;
  std::map<geo::TileId, std::optional<HeightTile>> heights_;
  std::map<geo::TileId, std::optional<ColorTile>> colours_;
};

}  // namespace vegstream::datasets::test
