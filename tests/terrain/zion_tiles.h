#pragma once
// Real heights for the terrain tests: the Zion SRTM sample imported once per test process
// (datasets::importGeoTiff, max zoom 11, no imagery) into a per-process directory under
// VEGSTREAM_TEST_TMP, removed when the process ends. Tiles are read back through the codec.

#include <unistd.h>

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

namespace vegstream::terrain::test {

class ZionTiles {
 public:
  static ZionTiles& get() {
    static ZionTiles instance;
    return instance;
  }
  const datasets::DatasetMeta& meta() const { return meta_; }

  // The tile, or an exception when the import wrote none there (tests pick tiles with data).
  const datasets::HeightTile& tile(const geo::TileId& id) {
    auto it = tiles_.find(id);
    if (it == tiles_.end()) {
      auto t = datasets::readHeightTile(datasets::elevationTilePath(dir_, id), id, meta_.elevationEncoding);
      if (!t) throw std::runtime_error("no Zion tile " + geo::toString(id) + ": " + t.error().message);
      it = tiles_.emplace(id, std::move(*t)).first;
    }
    return it->second;
  }

  ~ZionTiles() {
    std::error_code ec;
    std::filesystem::remove_all(root_, ec);
  }

 private:
  ZionTiles() {
    root_ = std::filesystem::path(VEGSTREAM_TEST_TMP) / ("terrain-" + std::to_string(::getpid()));
    std::filesystem::remove_all(root_);
    std::filesystem::create_directories(root_);
    dir_ = root_ / "zion";
    datasets::GeoTiffImportOptions options;
    options.dem = std::filesystem::path(VEGSTREAM_DATASETS_DIR) / "zion" / "srtm.tif";
    options.out = dir_;
    options.maxZoom = 11;
    options.threads = 2;
    datasets::NullProgress progress;
    auto meta = datasets::importGeoTiff(options, makeNullLogger(), progress);
    if (!meta) throw std::runtime_error("Zion import failed: " + meta.error().message);
    meta_ = *meta;
  }

  std::filesystem::path root_, dir_;
  datasets::DatasetMeta meta_;
  std::map<geo::TileId, datasets::HeightTile> tiles_;
};

}  // namespace vegstream::terrain::test
