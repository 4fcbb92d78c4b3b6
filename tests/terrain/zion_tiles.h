#pragma once
// Real heights for the terrain tests: the Zion SRTM sample (datasets::importGeoTiff, max zoom 11,
// no imagery) imported once per build of the test program for all its test processes
// (cachedFixture), on the first get() inside a test. Tiles are read back through the codec.

#include <filesystem>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>

#include "core/log.h"
#include "datasets/dataset_format.h"
#include "datasets/geotiff_import.h"
#include "datasets/progress.h"
#include "datasets/tile_codec.h"
#include "tests/support/test_dirs.h"

namespace vegstream::terrain::test {

class ZionTiles {
 public:
  static ZionTiles& get() {
    static ZionTiles instance;
    return instance;
  }
  const datasets::DatasetMeta& meta() const { return meta_; }
  const std::filesystem::path& dir() const { return dir_; }

  // The tile, or an exception when the import wrote none there (tests pick tiles with data).
  const datasets::HeightTile& tile(const geo::TileId& id) {
    auto it = tiles_.find(id);
    if (it == tiles_.end()) {
      auto t = datasets::readHeightTile(datasets::elevationTilePath(dir_, id), id, meta_.elevationEncoding,
                                        datasets::kTileSize);
      if (!t) throw std::runtime_error("no Zion tile " + geo::toString(id) + ": " + t.error().message);
      it = tiles_.emplace(id, std::move(*t)).first;
    }
    return it->second;
  }

  // The import failing throws: the test that asked fails with the message.
 private:
  ZionTiles() {
    auto dir = testing::cachedFixture(
        "terrain-zion-z11", testing::programKey(), [](const std::filesystem::path& out) -> Status {
          datasets::GeoTiffImportOptions options;
          options.dem = {(std::filesystem::path(VEGSTREAM_DATASETS_DIR) / "zion" / "srtm.tif").string()};
          options.out = out;
          options.maxZoom = 11;
          options.threads = 2;
          datasets::NullProgress progress;
          auto meta = datasets::importGeoTiff(options, makeNullLogger(), progress);
          if (!meta) return meta.error();
          return {};
        });
    if (!dir) throw std::runtime_error("Zion import failed: " + dir.error().message);
    dir_ = *dir;
    auto meta = datasets::readDatasetMeta(dir_);
    if (!meta) throw std::runtime_error("Zion import unreadable: " + meta.error().message);
    meta_ = *meta;
  }

  std::filesystem::path dir_;
  datasets::DatasetMeta meta_;
  std::map<geo::TileId, datasets::HeightTile> tiles_;
};

}  // namespace vegstream::terrain::test
